// readInputFile: regular files only, opened without blocking (input_file.h).

#include "util/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace radiant {

namespace {

std::string kindOf(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

std::string sizeText(uint64_t bytes) {
  if (bytes >= (uint64_t(1) << 30) && bytes % (uint64_t(1) << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (uint64_t(1) << 20) && bytes % (uint64_t(1) << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

/// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

/// Opens `path` for reading without blocking (a FIFO with no writer opens at
/// once instead of waiting for one) and checks that what it opened is a
/// regular file.
InputFileRead openRegular(const std::string &path, Descriptor &file, struct stat &info) {
  InputFileRead result;
  file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (file.fd < 0) {
    result.status =
        errno == ENOENT || errno == ENOTDIR ? InputFileRead::Status::Missing : InputFileRead::Status::Unreadable;
    result.reason = std::strerror(errno);
    return result;
  }
  if (::fstat(file.fd, &info) != 0) {
    result.reason = std::strerror(errno);
    return result;
  }
  if (!S_ISREG(info.st_mode)) {
    result.status = InputFileRead::Status::NotRegular;
    result.kind = kindOf(info.st_mode);
    return result;
  }
  result.status = InputFileRead::Status::Read;
  return result;
}

}  // namespace

InputFileRead tryReadInputFile(const std::string &path, uint64_t maxBytes) {
  Descriptor file{-1};
  struct stat info {};
  InputFileRead result = openRegular(path, file, info);
  if (!result.ok()) return result;
  if (uint64_t(info.st_size) > maxBytes) {
    result.status = InputFileRead::Status::TooLarge;
    result.size = uint64_t(info.st_size);
    return result;
  }
  // O_NONBLOCK has no effect on a regular file's reads. The size is a hint: a
  // file that grows while it is read is read to its end, up to the bound.
  result.bytes.resize(size_t(info.st_size));
  size_t got = 0;
  for (;;) {
    if (got == result.bytes.size()) {
      if (result.bytes.size() > maxBytes) {
        result.status = InputFileRead::Status::TooLarge;
        result.size = result.bytes.size();
        result.bytes.clear();
        return result;
      }
      result.bytes.resize(std::max<size_t>(result.bytes.size() * 2, 4096));
    }
    const ssize_t n = ::read(file.fd, result.bytes.data() + got, result.bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      result.status = InputFileRead::Status::Unreadable;
      result.reason = std::strerror(errno);
      result.bytes.clear();
      return result;
    }
    if (n == 0) break;
    got += size_t(n);
  }
  result.bytes.resize(got);
  return result;
}

std::string readInputFilePrefix(const std::string &path, size_t bytes) {
  Descriptor file{-1};
  struct stat info {};
  if (!openRegular(path, file, info).ok()) return "";
  std::string prefix(bytes, '\0');
  size_t got = 0;
  while (got < bytes) {
    const ssize_t n = ::read(file.fd, prefix.data() + got, bytes - got);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    got += size_t(n);
  }
  prefix.resize(got);
  return prefix;
}

InputFileRead checkInputFile(const std::string &path) {
  Descriptor file{-1};
  struct stat info {};
  return openRegular(path, file, info);
}

std::string inputFileProblem(const InputFileRead &read, const std::string &named, uint64_t maxBytes) {
  switch (read.status) {
    case InputFileRead::Status::Read:
      return "";
    case InputFileRead::Status::Missing:
      return "cannot open " + named;
    case InputFileRead::Status::Unreadable:
      return "cannot open " + named + (read.reason.empty() ? "" : " (" + read.reason + ")");
    case InputFileRead::Status::NotRegular:
      return named + " is not a regular file (it is " + read.kind + "): Radiant reads only regular files";
    case InputFileRead::Status::TooLarge:
      return named + " is larger than " + sizeText(maxBytes) + " (it has " + std::to_string(read.size) + " bytes)";
  }
  return "cannot read " + named;
}

std::string readInputFile(const std::string &path, const InputLocation &where, const std::string &what,
                          uint64_t maxBytes) {
  InputFileRead read = tryReadInputFile(path, maxBytes);
  if (!read.ok()) throw InputError(where, inputFileProblem(read, what + " '" + path + "'", maxBytes));
  return std::move(read.bytes);
}

std::optional<std::string> inputFileCheck(const std::string &path, const std::string &what) {
  const InputFileRead opened = checkInputFile(path);
  if (opened.ok()) return std::nullopt;
  return inputFileProblem(opened, what + " '" + path + "'");
}

}  // namespace radiant
