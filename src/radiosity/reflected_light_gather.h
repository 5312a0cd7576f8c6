// The reflected light of a stochastic solution at the nodes of a tessellated
// model, by a final gather: at each node, rays over the hemisphere read the
// solution where they land.
//
// Stochastic Jacobi (radiosity/stochastic_jacobi.cpp) gives an element the
// power of the rays that landed on it. A facet of a tessellated model holds
// a handful of them, far too few for its own value; pooling the rays of its
// neighbours (reflected_light_density.h) trades that noise for blur, and on
// a curved model the blur is a bias: the rays that landed on the facets
// around a node faced other ways and saw other light (the underside of a
// sphere on a floor came out 14 % bright on cornell-knots). A gather asks
// the other question: what does the node itself see? Every ray leaves the
// node with a cosine-distributed direction and reads the radiosity of the
// element it hits, less its emission (the light straight from the emitters
// is computed exactly at the nodes already: node_direct_light.h), so
//
//   H_reflected(x) = ∫ L(x, ω) cos θ dω ≈ (1/N) Σ_k (B − E)(hit_k)
//
// (cosine sampling: pdf cos θ / π, and L = B/π on a diffuse surface;
// C&W eq. 2.38 and §9.3.2's gather, as the final gather of photon mapping
// and Lischinski et al.'s "local pass"). What a ray reads is a mean over
// one element, which the walls hold to a few per cent and a facet to its
// few rays; the gather averages many of them, so its error is the
// quadrature's (stratified: N^(-3/4) for a piecewise smooth integrand), not
// the facets'. The node's direction is its pool's (Solution::nodePools):
// coincident nodes of one smooth surface gather once, with their mean normal.
#pragma once

#include <vector>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"

namespace radiant {

/// The irradiance of the light reflected at least once, W·m⁻², gathered at
/// `nodes` (each the first node of its pool, Solution::nodePools) from
/// `solution`'s element radiosities less their emission; `raysPerNode`
/// stratified cosine-distributed rays each (rounded to a square). Each
/// value is then the weighted mean of the gathers of `nodes` within
/// `smoothingRadius` metres facing the same way on the same object (0: none;
/// the stochastic solver uses 1/256 of the scene, a few facets of a model).
/// Returns one value per entry of `nodes`. Deterministic for `seed`,
/// whatever the threads; split over the MPI ranks and shared bit for bit.
std::vector<Bands> gatherReflectedIrradiance(const RayTracer &tracer, const Solution &solution,
                                             const std::vector<uint32_t> &nodes, int raysPerNode,
                                             double smoothingRadius, uint64_t seed, int threads);

}  // namespace radiant
