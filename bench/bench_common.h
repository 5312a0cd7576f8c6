// What the benchmark programs in bench/ share: the command line
// `[scene.json] [--FLAG VALUE]` and the load average they record.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace radiant::bench {

inline double loadAverage() {
  double load[1] = {-1};
  return getloadavg(load, 1) == 1 ? load[0] : -1;
}

/// Parses `[scene.json] [--flag VALUE]` into `scenePath` and `value`; prints
/// the usage and returns false on anything else.
inline bool parseSceneAndNumber(int argc, char **argv, const char *flag, const char *valueName,
                                std::string &scenePath, double &value) {
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
