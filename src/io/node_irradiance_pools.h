// The solution file's node irradiance once per pool of coincident nodes
// (docs/solution-format.md, content bit 11): the stochastic solver's direct
// light at the nodes is the same at every node of a pool, and a tessellated
// model has several nodes per vertex, so a value per pool is a quarter of
// the bytes of a value per node on a quad-meshed model.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "radiosity/solution.h"

namespace radiant {

/// Whether every node's irradiance (direct and reflected), rounded to f32 as
/// the file keeps it, has the very bits of its pool's first node's
/// (`pools`: Solution::nodePools): then one value per pool reads back
/// exactly as one per node. hierarchical-exact's values are evaluated a hair
/// inside each patch and are not.
bool nodeIrradianceIsPooled(const Solution &s, const std::vector<uint32_t> &pools);

/// The pools' first nodes, in increasing order: whose values the file holds.
std::vector<uint32_t> poolHeads(const std::vector<uint32_t> &pools);

/// Spreads one value per pool (s.nodeDirectIrradiance and
/// s.nodeIndirectIrradiance, in the order of poolHeads) over every node of
/// the pool, on the mesh the reader has derived. Returns an error message
/// when the counts differ, else an empty string.
std::string spreadPooledNodeIrradiance(Solution &s);

}  // namespace radiant
