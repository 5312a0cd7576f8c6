// What the benchmark programs in bench/ share: the command line
// `[scene.json] [--FLAG VALUE]` and the load average they record.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace radiant::bench {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// A reference image's variance file: NAME.var.EXT beside NAME.EXT.
inline std::string variancePathFor(const std::string &referencePath) {
  std::filesystem::path p(referencePath);
  return (p.parent_path() / (p.stem().string() + ".var" + p.extension().string())).string();
}

inline double loadAverage() {
  double load[1] = {-1};
  return getloadavg(load, 1) == 1 ? load[0] : -1;
}

/// Parses `[scene.json] [--flag VALUE]` into `scenePath` and `value`; prints
/// the usage and returns false on anything else.
inline bool parseSceneAndNumber(int argc, char **argv, const char *flag, const char *valueName, std::string &scenePath,
                                double &value) {
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == flag && i + 1 < argc) {
      value = std::atof(argv[++i]);
    } else if (arg.rfind("--", 0) == 0) {
      std::fprintf(stderr, "usage: %s [scene.json] [%s %s]\n", argv[0], flag, valueName);
      return false;
    } else {
      scenePath = arg;
    }
  }
  return true;
}

}  // namespace radiant::bench
