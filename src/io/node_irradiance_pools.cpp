#include "io/node_irradiance_pools.h"

#include <fmt/format.h>

#include <cstring>

namespace radiant {

bool nodeIrradianceIsPooled(const Solution &s, const std::vector<uint32_t> &pools) {
  for (const std::vector<Bands> *values : {&s.nodeDirectIrradiance, &s.nodeIndirectIrradiance})
    for (size_t v = 0; v < pools.size(); ++v)
      for (int b = 0; b < kBandCount; ++b) {
        const float own = float((*values)[v][b]), head = float((*values)[pools[v]][b]);
        if (std::memcmp(&own, &head, sizeof own) != 0) return false;
      }
  return true;
}

std::vector<uint32_t> poolHeads(const std::vector<uint32_t> &pools) {
  std::vector<uint32_t> heads;
  for (uint32_t v = 0; v < pools.size(); ++v)
    if (pools[v] == v) heads.push_back(v);
  return heads;
}

std::string spreadPooledNodeIrradiance(Solution &s) {
  const std::vector<uint32_t> pools = s.nodePools();
  std::vector<uint32_t> poolIndex(pools.size(), 0);
  const std::vector<uint32_t> heads = poolHeads(pools);
  if (heads.size() != s.nodeDirectIrradiance.size() || heads.size() != s.nodeIndirectIrradiance.size())
    return fmt::format("{} pools of node irradiance for a mesh of {} pools", s.nodeDirectIrradiance.size(),
                       heads.size());
  for (size_t i = 0; i < heads.size(); ++i) poolIndex[heads[i]] = uint32_t(i);
  for (std::vector<Bands> *values : {&s.nodeDirectIrradiance, &s.nodeIndirectIrradiance}) {
    std::vector<Bands> perNode(pools.size());
    for (uint32_t v = 0; v < pools.size(); ++v) perNode[v] = (*values)[poolIndex[pools[v]]];
    *values = std::move(perNode);
  }
  return {};
}

}  // namespace radiant
