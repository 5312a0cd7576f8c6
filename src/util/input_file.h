// The one way Radiant reads an input file: every reader (scene JSON, OBJ/MTL,
// glTF and its buffers, MGF and its includes, IES/EULUMDAT, textures, images,
// solution files, checkpoints) takes its bytes from readInputFile.
//
// Only a regular file is read. A FIFO, a character device (/dev/zero, a
// terminal), a socket or a directory named where a file is expected is refused
// with "… is not a regular file": a FIFO would block forever in open() or
// read() until something writes to it, a device can stream without end. The
// file is opened without blocking (O_NONBLOCK) and the check made on what was
// opened (fstat), so a file swapped for a FIFO after a name check cannot hang
// the reader either.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "util/error.h"

namespace radiant {

/// No input file of any kind is read past this; readers with a tighter bound pass their own.
constexpr uint64_t kMaxInputFileBytes = uint64_t(4) << 30;

/// The result of one read: the bytes, or why there are none.
struct InputFileRead {
  enum class Status { Read, Missing, NotRegular, TooLarge, Unreadable };
  Status status = Status::Unreadable;
  std::string bytes;   ///< the whole file when status is Read
  std::string kind;    ///< what a NotRegular path is: "a FIFO", "a directory", …
  std::string reason;  ///< strerror's text when Missing or Unreadable
  uint64_t size = 0;   ///< the size of a TooLarge file
  bool ok() const { return status == Status::Read; }
};

/// Reads the regular file at `path` whole, never blocking on a FIFO or a device.
InputFileRead tryReadInputFile(const std::string &path, uint64_t maxBytes = kMaxInputFileBytes);

/// The first `bytes` bytes of the regular file at `path` (fewer if it is
/// shorter), or "" when it is not a regular file or cannot be read: for a
/// format told by its signature before the reader that names problems runs.
std::string readInputFilePrefix(const std::string &path, size_t bytes);

/// Opens the file at `path` as tryReadInputFile does, and reads nothing: status
/// Read when it is a regular file that can be read.
InputFileRead checkInputFile(const std::string &path);

/// The sentence for a failed read of the file `named` ("glTF buffer 'a.bin'",
/// "texture 'x.png' named by map_Kd"):
///   cannot open <named>                      (no such file)
///   cannot open <named> (Permission denied)
///   <named> is not a regular file (it is a FIFO): Radiant reads only regular files
///   <named> is larger than <maxBytes> (it has N bytes)
std::string inputFileProblem(const InputFileRead &read, const std::string &named,
                             uint64_t maxBytes = kMaxInputFileBytes);

/// The bytes of the regular file at `path`; throws InputError at `where` with
/// inputFileProblem's sentence otherwise.
std::string readInputFile(const std::string &path, const InputLocation &where, const std::string &what,
                          uint64_t maxBytes = kMaxInputFileBytes);

/// Why `path` cannot be read as a regular file (inputFileProblem's sentence
/// for "<what> '<path>'"), or nothing when it can: for a name checked before it
/// is read, or that a library then opens by name (OpenEXR).
std::optional<std::string> inputFileCheck(const std::string &path, const std::string &what);

}  // namespace radiant
