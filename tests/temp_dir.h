// A scratch folder for a test's files, removed with everything in it at
// the end of the test.
#pragma once

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>

namespace radiant::test {

class TempDir {
 public:
  /// `prefix` names the folder (radiant-PREFIX-PID-N under the system's temporary folder).
  explicit TempDir(const std::string &prefix) {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("radiant-" + prefix + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir &) = delete;
  TempDir &operator=(const TempDir &) = delete;
  /// Writes `text` to the file `name`; its path.
  std::string write(const std::string &name, const std::string &text) const {
    std::ofstream(path_ / name, std::ios::binary) << text;
    return file(name);
  }
  /// Makes a FIFO called `name`; its path.
  std::string fifo(const std::string &name) const {
    EXPECT_EQ(::mkfifo(file(name).c_str(), 0600), 0) << name;
    return file(name);
  }
  std::string file(const std::string &name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace radiant::test
