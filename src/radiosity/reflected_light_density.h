// The reflected light of a stochastic solution at the mesh's nodes, with the
// noise of each node's own few rays pooled away: a density estimate of the
// rays' deposits over a neighbourhood large enough to hold enough of them.
//
// Stochastic Jacobi (radiosity/stochastic_jacobi.cpp) gives an element the
// power of the rays that landed on it, with a relative error of about 1/√k
// for k rays. Its rays are spread over the surfaces by area and light, so an
// element far smaller than the scene's average (a facet of a tessellated
// model: 10⁵ of them on a sphere) gets a handful, and the display shows that
// noise as speckle. The light reflected at least once varies slowly (it is
// an integral over the whole hemisphere), so its irradiance at a point may
// be estimated from the power that landed on the surface around it, as a
// photon map estimates it from the photons around it (Jensen 1996; in
// radiosity, the density estimation of Shirley, Wade, Hubbard, Zareski,
// Walter & Greenberg, "Global illumination via density estimation", EGWR
// 1995): H(x) ≈ Σ wᵢ Pᵢ / Σ wᵢ Aᵢ over the elements i around x, of the same
// object and facing the same way, with a smooth weight w of their distance.
//
// Where a node's own elements already hold enough rays (a wall's large
// elements, hundreds each) it keeps their area-weighted mean, the usual node
// value, which follows the light as closely as the mesh does. Elsewhere the
// neighbourhood is the smallest of a ladder of grids (cell sizes 1/256 of the
// scene's extent, doubling) whose cells around the node hold enough rays:
// the estimate trades as little blur for as much noise as the rays allow.
#pragma once

#include <functional>
#include <vector>

#include "radiosity/solution.h"

namespace radiant {

/// The irradiance of the light reflected at least once at every node of
/// `solution`'s mesh, W·m⁻²: `power` is the reflected power each element
/// received, W per band, and `rays` the number of rays that brought it.
/// A node whose elements (with their pool's: Solution::nodePools) received
/// at least `enoughRays` keeps their area-weighted mean (Solution::nodeValues);
/// any other takes the density estimate over the smallest neighbourhood that
/// holds that many, or the largest there is. Deterministic, in parallel.
/// With `estimateSparse`, every node takes its estimates instead
/// (reflected_light_gather.h): it is called once for the nodes with too
/// few rays and once for those with enough (`enoughRays` true).
using SparseNodeEstimate = std::function<std::vector<Bands>(const std::vector<uint32_t> &nodes, bool enoughRays)>;
std::vector<Bands> reflectedIrradianceAtNodes(const Solution &solution, const std::vector<Bands> &power,
                                              const std::vector<double> &rays, double enoughRays, int threads,
                                              const SparseNodeEstimate &estimateSparse = {});

}  // namespace radiant
