// The direct light at the nodes of a uniform mesh, exact: what the
// stochastic solver (radiosity/stochastic_jacobi.cpp) displays as the light
// arriving straight from the emitters, instead of the first iteration's rays.
//
// The light that arrives straight from the emitters is most of what a room
// shows, and it holds the shadows. Shot with rays, each element gets it with
// the noise of the few rays that reached it (about 1/√k for k rays): the
// facets of a tessellated model, far smaller than a pixel's share of the
// rays, show it as speckle, and a shadow is only as sharp as the elements
// under it. Computed at the nodes by backprojection (radiosity/backprojection.h,
// as hierarchical-exact does; a fixed grid of shadow rays where a
// tessellated model lies between a node and a light), it has no noise, and
// the display interpolates it between the nodes (Solution::nodeDirectIrradiance).
// The rays are left the light reflected at least once, which is dimmer and smoother.
#pragma once

#include <vector>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// The direct light of a mesh: at its nodes and averaged over its elements.
struct MeshDirectLight {
  /// W·m⁻² per band at every node; coincident nodes of one smooth surface
  /// share one value (Solution::nodePools), T-vertices their edge's interpolation.
  std::vector<Bands> atNodes;
  /// The mean over each element, W·m⁻²: what it reflects on, so the power
  /// the solver starts from is the light that arrived (energy balance).
  std::vector<Bands> ofElements;
};

/// The irradiance straight from the scene's emitters (area and point
/// lights) on `solution`'s mesh. At the nodes: once per pool of coincident
/// nodes of one smooth surface, with the mean of their patches' normals.
/// Over an element: the mean of its corners where it is tiny against its
/// distance to the nearest light (the facets of a tessellated model), else
/// a midpoint rule of 3 × 3 to 16 × 16 points, finer the larger it is
/// against that distance (as meanPointLightIrradiance). Exact by
/// backprojection up to `maxExactOccluders` faces in a point's shaft to a
/// light, sampled beyond (DirectIrradiance). Split over the MPI ranks and
/// summed; deterministic, whatever the threads and ranks.
MeshDirectLight directLightOfMesh(const RayTracer &tracer, const Solution &solution, int threads,
                                  size_t maxExactOccluders = 48);

}  // namespace radiant
