// A file's extension as the program compares it: lower case, with its dot
// (".glb", ".exr"), or empty. The one place the readers and writers that choose
// by extension take it from.
#pragma once

#include <cctype>
#include <filesystem>
#include <string>

namespace radiant {

inline std::string lowercaseExtension(const std::string &path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char &c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

/// A file beside `path`, its stem extended: "out.exr", ".solve" → "out.solve.exr".
inline std::string suffixedFilePath(const std::string &path, const std::string &suffix) {
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

/// The file of one pass beside `path`: "out.exr", 3 → "out.pass3.exr" (a
/// multipass image, a spectral or multipass pass's checkpoint).
inline std::string passFilePath(const std::string &path, int pass) {
  return suffixedFilePath(path, ".pass" + std::to_string(pass));
}

}  // namespace radiant
