// Writing a file so that a failure never leaves a partial file over a good
// one: write a temporary file in the target's folder, then rename it.
#pragma once

#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>

namespace radiant {

/// Calls write(temporaryPath), then renames the temporary onto `path`. On any
/// exception the temporary is removed and std::runtime_error names `path`.
template <typename WriteFunction>
void writeAtomically(const std::string &path, WriteFunction write) {
  std::filesystem::path target(path);
  std::random_device entropy;
  std::filesystem::path temporary =
      target.parent_path() / ("." + target.filename().string() + ".tmp" + std::to_string(entropy() % 1000000));
  try {
    write(temporary.string());
    std::filesystem::rename(temporary, target);
  } catch (const std::exception &e) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
}

}  // namespace radiant
