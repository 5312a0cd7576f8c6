// A tree mesh refined unevenly, so that it has T-vertices (nodes of small
// elements inside a large neighbour's edge), two levels deep: what the
// export and round-trip tests need without running an adaptive solver.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace radiant::test {

/// The scene's tree mesh at `maxEdgeLength` metres, every third element split, twice.
inline RadiosityMesh refinedTreeMesh(const Scene &scene, double maxEdgeLength) {
  MeshOptions options;
  options.maxEdgeLength = maxEdgeLength;
  RadiosityMesh mesh = buildTreeMesh(scene, options);
  for (int round = 0; round < 2; ++round) {
    std::vector<double> error(mesh.elements.size(), 0.0);
    for (size_t e = 0; e < error.size(); e += 3) error[e] = 1;
    refineMesh(mesh, error, 0.5, 100000);
  }
  return mesh;
}

}  // namespace radiant::test
