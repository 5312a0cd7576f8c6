// What a checkpoint records of its inputs (render/checkpoint.h,
// radiosity/solve_checkpoint.h): a hash of a file's bytes.
#pragma once

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace radiant {

/// FNV-1a (64 bits) of the file's bytes, in hex; "" for no path, "unreadable" when it cannot be read.
inline std::string fileFingerprint(const std::string &path) {
  if (path.empty()) return "";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "unreadable";
  uint64_t hash = 0xcbf29ce484222325ULL;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) hash = (hash ^ uint8_t(buffer[i])) * 0x100000001b3ULL;
    if (!in) break;
  }
  return fmt::format("{:016x}", hash);
}

}  // namespace radiant
