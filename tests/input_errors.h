// The message of the InputError that a call throws: what the tests of
// Radiant's refusals compare (docs/cli.md "Errors").
#pragma once

#include <string>

#include "scene/load_scene.h"
#include "util/error.h"

namespace radiant::test {

/// The message of the InputError `call` throws ("" if it throws none).
template <typename F>
std::string inputErrorOf(F &&call) {
  try {
    call();
  } catch (const InputError &e) {
    return e.what();
  }
  return "";
}

/// The loader's message for the scene file at `path` ("" if it loads).
inline std::string loadErrorOf(const std::string &path) {
  return inputErrorOf([&] { loadScene(path); });
}

}  // namespace radiant::test
