// The shape of the sources: the stages of src/ include only earlier stages
// (README.md, "Layout") — a folder that includes a later one is an arrow
// against the data flow, and the test names the file and the include — and
// no file of src/ or app/ grows past 600 lines (one method per file; the CIE
// 1931 observer's table is data, and excepted).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

// In include order, as README.md's layout table lists them.
const std::vector<std::string> kStages = {"util", "cluster",   "colour", "texture", "scene",   "raytrace",
                                          "mesh", "radiosity", "io",     "render",  "display", "export"};

int stageIndex(const std::string &folder) {
  auto it = std::find(kStages.begin(), kStages.end(), folder);
  return it == kStages.end() ? -1 : int(it - kStages.begin());
}

TEST(Layering, EveryStageIncludesOnlyEarlierStages) {
  const std::filesystem::path src = std::filesystem::path(RADIANT_SOURCE_DIR) / "src";
  const std::regex include(R"(^\s*#\s*include\s*"([a-z_]+)/[^"]+")");
  size_t files = 0, includes = 0;
  std::vector<std::string> backwards;
  for (const auto &entry : std::filesystem::recursive_directory_iterator(src)) {
    const std::string extension = entry.path().extension().string();
    if (!entry.is_regular_file() || (extension != ".h" && extension != ".cpp")) continue;
    const std::string folder = entry.path().parent_path().filename().string();
    const int own = stageIndex(folder);
    ASSERT_GE(own, 0) << entry.path() << ": folder '" << folder << "' is not a stage of the layout";
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    int lineNumber = 0;
    while (std::getline(in, line)) {
      ++lineNumber;
      std::smatch m;
      if (!std::regex_search(line, m, include)) continue;
      ++includes;
      const int target = stageIndex(m[1].str());
      if (target < 0) continue;  // a library's header ("stb/…"), not a stage
      if (target > own)
        backwards.push_back(std::filesystem::relative(entry.path(), src).string() + ":" + std::to_string(lineNumber) +
                            " includes " + m[1].str() + "/");
    }
  }
  EXPECT_GT(files, 100u);  // the scan found the sources
  EXPECT_GT(includes, 200u);
  for (const std::string &b : backwards) ADD_FAILURE() << b;
}

TEST(Layering, NoSourceFileOver600Lines) {
  constexpr int kMaxLines = 600;
  size_t files = 0;
  for (const char *folder : {"src", "app"}) {
    const std::filesystem::path root = std::filesystem::path(RADIANT_SOURCE_DIR) / folder;
    for (const auto &entry : std::filesystem::recursive_directory_iterator(root)) {
      const std::string extension = entry.path().extension().string();
      if (!entry.is_regular_file() || (extension != ".h" && extension != ".cpp")) continue;
      if (entry.path().filename() == "cie1931.cpp") continue;  // the observer's table: data, not code
      ++files;
      std::ifstream in(entry.path());
      int lines = 0;
      for (std::string line; std::getline(in, line);) ++lines;
      EXPECT_LE(lines, kMaxLines) << entry.path() << ": split it, one method per file";
    }
  }
  EXPECT_GT(files, 100u);
}

}  // namespace
