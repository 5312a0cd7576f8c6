// The solution file (docs/solution-format.md): a radiosity solution saved by
// `radiant solve -o` and reused by `radiant render --solution`.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

/// 4: a pass count, then one solution per spectral pass (one for RGB scenes).
/// 6: the light through translucent faces per element (Solution::transmittedDirect).
/// 7: compact, at most 100 bytes per element of a large mesh: values as f32, the
/// geometry, ρ, E, B and the node values derived on reading (io/solution_geometry.h).
constexpr uint32_t kSolutionFormatVersion = 7;

/// A hash of what the solution depends on: geometry, faces and the
/// radiometric material values. A solution is refused for a scene whose
/// fingerprint differs.
uint64_t sceneFingerprint(const Scene &scene);

/// Writes atomically (temporary file, then rename). An RGB scene's solution.
void writeSolution(const Solution &solution, const Scene &scene, const std::string &path);
/// One solution per pass: a spectral scene's ⌈N/3⌉ (scene/spectral_scene.h), in pass order.
void writeSolutionPasses(std::span<const Solution> passes, const Scene &scene, const std::string &path);

/// Reads a solution and checks it belongs to `scene`; throws InputError naming
/// the file and what is wrong (not a solution file, another format version,
/// another scene, truncated or inconsistent data).
Solution readSolution(const std::string &path, const Scene &scene);
/// All passes of a solution file: one for an RGB scene, ⌈N/3⌉ for a spectral one.
std::vector<Solution> readSolutionPasses(const std::string &path, const Scene &scene);

}  // namespace radiant
