// The binary reading and writing that the checkpoint files share
// (render/checkpoint.h, render/multipass_checkpoint.h): values in host byte
// order, length-prefixed text, and a reader that names the file and what
// it was reading when the file ends early or holds nonsense.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "util/error.h"
#include "util/spectrum.h"

namespace radiant {

static_assert(sizeof(Bands) == kBandCount * sizeof(double), "a film's Bands are written as kBandCount doubles");

class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::ofstream &out) : out_(out) {}
  template <typename T>
  void value(const T &v) {
    out_.write(reinterpret_cast<const char *>(&v), sizeof v);
  }
  void bytes(const void *data, size_t size) { out_.write(static_cast<const char *>(data), std::streamsize(size)); }
  void text(const std::string &s) {
    value(uint32_t(s.size()));
    bytes(s.data(), s.size());
  }
  template <typename T>
  void array(const std::vector<T> &v) {
    bytes(v.data(), v.size() * sizeof(T));
  }

 private:
  std::ofstream &out_;
};

class CheckpointReader {
 public:
  /// `kind`: what the file should be, for messages ("render checkpoint").
  CheckpointReader(std::ifstream &in, const std::string &path, const char *kind = "render checkpoint")
      : in_(in), path_(path), kind_(kind) {}
  template <typename T>
  T value(const char *what) {
    T v{};
    bytes(&v, sizeof v, what);
    return v;
  }
  void bytes(void *data, size_t size, const char *what) {
    if (!in_.read(static_cast<char *>(data), std::streamsize(size)))
      fail(fmt::format("the file ends inside {} (truncated?)", what));
  }
  /// Fills `v`, already sized as the job's (so a damaged file cannot ask for memory).
  template <typename T>
  void array(std::vector<T> &v, const char *what) {
    bytes(v.data(), v.size() * sizeof(T), what);
  }
  std::string text(const char *what) {
    constexpr uint32_t kMaxText = 1 << 20;
    const uint32_t size = value<uint32_t>(what);
    if (size > kMaxText) fail(fmt::format("{} is {} bytes long, more than a checkpoint holds", what, size));
    std::string s(size, '\0');
    bytes(s.data(), size, what);
    return s;
  }
  bool atEnd() { return in_.peek() == std::char_traits<char>::eof(); }
  [[noreturn]] void fail(const std::string &message) const {
    throw InputError(InputLocation{path_}, fmt::format("not a usable {}: {}", kind_, message));
  }

 private:
  std::ifstream &in_;
  const std::string &path_;
  const char *kind_;
};

/// The start of every checkpoint file: its magic, its format's version and the job it belongs to.
inline void writeCheckpointHeader(CheckpointWriter &w, const std::string &magic, uint32_t version,
                                  const std::string &job) {
  w.bytes(magic.data(), magic.size());
  w.value(version);
  w.text(job);
}

/// Reads and checks that start; refuses (naming the file) another kind of
/// file, another version, or a checkpoint of another job.
inline void readCheckpointHeader(CheckpointReader &r, const std::string &magic, uint32_t version,
                                 const std::string &job) {
  std::string found(magic.size(), '\0');
  r.bytes(found.data(), found.size(), "the header");
  if (found != magic) r.fail("it does not start with " + magic);
  if (const uint32_t v = r.value<uint32_t>("the header"); v != version)
    r.fail(fmt::format("version {}; this radiant reads version {}", v, version));
  if (r.text("the job description") != job)
    r.fail(
        "it belongs to another job (a different scene file, image size, method, samples, seed or option); "
        "remove it to start afresh");
}

}  // namespace radiant
