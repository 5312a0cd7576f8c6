// The stochastic solver's mesh when the direct light is exact at its nodes
// (radiosity/node_direct_light.h): the surfaces larger than an element
// refined where that light does not interpolate, so that contact shadows
// and penumbrae are in the mesh (issue 36: an engine on a floor, a chair's
// leg).
//
// The display interpolates the direct light between the nodes. On a uniform
// mesh of 1/32 of the scene (17 mm in the Cornell room) the shadow a model
// casts where it stands on the floor is one element wide: the
// interpolation smears it into a bright band around the model's foot, the
// largest error left on the scenes users bring. This is the refinement
// hierarchical-exact makes (radiosity/direct_refinement.h): every leaf
// tested at the points its children would add against the bilinear
// interpolation of its corners, split where the exact light disagrees by
// more than the tolerance, down to 1/256 of the scene. Only the patches
// the uniform mesh divided (walls, floors, a model's large faces) are
// refined: a tessellated model's facets are already smaller than an
// element, and testing each would cost more than its nodes' light.
#pragma once

#include "mesh/mesh.h"
#include "radiosity/solver.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// A mesh refined to the direct light, and that light where the refinement
/// evaluated it (NaN elsewhere): at the nodes of the refined patches, and
/// their elements' means (Simpson's rule over the points tested, within
/// the tolerance of the light by construction).
struct DirectLightMesh {
  RadiosityMesh mesh;
  std::vector<Bands> nodeDirect, elementDirect;
};

/// buildTreeMesh(scene, meshOptions), then the leaves of patches of at least
/// four elements' area split until the exact direct irradiance interpolates
/// within options.directTolerance of the mean first-bounce radiosity over
/// those patches, down to options.directMinimumEdge (0: 1/256 of the
/// scene's extent) and at most options.maxElements leaves. Deterministic,
/// whatever the threads and MPI ranks.
DirectLightMesh buildDirectLightMesh(const Scene &scene, const RayTracer &tracer, const MeshOptions &meshOptions,
                                     const SolverOptions &options);

}  // namespace radiant
