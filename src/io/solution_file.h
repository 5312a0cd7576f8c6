// The solution file (docs/solution-format.md): a radiosity solution saved by
// `radiant solve -o` and reused by `radiant render --solution`.
#pragma once

#include <string>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

constexpr uint32_t kSolutionFormatVersion = 3;

/// A hash of what the solution depends on: geometry, faces and the
/// radiometric material values. A solution is refused for a scene whose
/// fingerprint differs.
uint64_t sceneFingerprint(const Scene &scene);

/// Writes atomically (temporary file, then rename).
void writeSolution(const Solution &solution, const Scene &scene, const std::string &path);

/// Reads a solution and checks it belongs to `scene`; throws InputError naming
/// the file and what is wrong (not a solution file, another format version,
/// another scene, truncated or inconsistent data).
Solution readSolution(const std::string &path, const Scene &scene);

}  // namespace radiant
