#include "radiosity/solution.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

#include "radiosity/transmission.h"
#include "raytrace/surface_detail.h"

namespace radiant {

Solution initialSolution(const Scene &scene, RadiosityMesh mesh) {
  Solution s;
  const size_t n = mesh.elements.size();
  s.reflectance.resize(n);
  s.emission.resize(n);
  for (size_t e = 0; e < n; ++e) {
    const Material &m = scene.materials[mesh.patchOf(static_cast<uint32_t>(e)).material];
    // Only the diffuse part takes part in radiosity; mirrors and glass are left
    // to the per-pixel passes (their diffuse reflectance is 0).
    s.reflectance[e] = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : Bands(0.0);
    // A textured surface takes part with its texture's mean over the element, ρ̄ (C&W eq. 9.11).
    if (m.diffuseTextureIndex >= 0 && s.reflectance[e].max() > 0) {
      const Element &element = mesh.elements[e];
      std::array<Vec3, 4> corners;
      for (int k = 0; k < element.vertexCount; ++k) corners[k] = mesh.nodes[element.nodes[k]];
      s.reflectance[e] = averageDiffuse(scene, mesh.patchOf(static_cast<uint32_t>(e)).face,
                                        std::span<const Vec3>(corners.data(), element.vertexCount));
    }
    s.emission[e] = m.emission * kPi;
  }
  s.transmittance = elementTransmittance(scene, mesh);
  s.radiosity = s.emission;
  s.direct.assign(n, Bands(0.0));
  s.indirect.assign(n, Bands(0.0));
  s.unshot = s.emission;
  s.irradiance.assign(n, Bands(0.0));
  s.mesh = std::move(mesh);
  for (size_t e = 0; e < n; ++e) s.stats.emittedPower += s.emission[e] * s.mesh.elements[e].area;
  for (const PointLight &light : scene.lights) s.stats.emittedPower += light.power();
  s.updateNodesAndErrors();
  return s;
}

Bands Solution::interpolate(const std::vector<Bands> &values, const MeshLocation &location) const {
  const Element &e = mesh.elements[location.element];
  std::array<double, 4> w = mesh.nodeWeights(location);
  Bands b(0.0);
  for (int k = 0; k < e.vertexCount; ++k) b += values[e.nodes[k]] * w[k];
  return b;
}

namespace {

/// FNV-1a over what the pools depend on: the nodes' places, patches and
/// shading normals, the cuts, and each patch's material and normal (a few ms
/// at 2·10⁶ nodes).
uint64_t poolFingerprint(const RadiosityMesh &mesh) {
  uint64_t hash = 0xcbf29ce484222325ULL;
  auto add = [&](const void *data, size_t bytes) {
    const auto *p = static_cast<const uint8_t *>(data);
    for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 0x100000001b3ULL;
  };
  auto addWords = [&](const void *data, size_t bytes) {  // 8 bytes a step: the node arrays are large
    const auto *p = static_cast<const uint8_t *>(data);
    size_t i = 0;
    for (; i + 8 <= bytes; i += 8) {
      uint64_t word;
      std::memcpy(&word, p + i, 8);
      hash = (hash ^ word) * 0x100000001b3ULL;
      hash ^= hash >> 29;
    }
    add(p + i, bytes - i);
  };
  const size_t sizes[] = {mesh.nodes.size(), mesh.nodePatch.size(), mesh.nodeOnCut.size(), mesh.patches.size(),
                          mesh.nodeShadingNormals.size()};
  add(sizes, sizeof sizes);
  addWords(mesh.nodeShadingNormals.data(), mesh.nodeShadingNormals.size() * sizeof(ShadingNormal));
  addWords(mesh.nodes.data(), mesh.nodes.size() * sizeof(Vec3));
  addWords(mesh.nodePatch.data(), mesh.nodePatch.size() * sizeof(uint32_t));
  addWords(mesh.nodeOnCut.data(), mesh.nodeOnCut.size());
  for (const Patch &patch : mesh.patches) {
    add(&patch.material, sizeof patch.material);
    add(&patch.normal, sizeof patch.normal);
  }
  return hash;
}

}  // namespace

std::vector<uint32_t> Solution::nodePools() const {
  const uint64_t fingerprint = poolFingerprint(mesh);
  std::lock_guard<std::mutex> lock(nodePoolMemo_->mutex);
  if (nodePoolMemo_->meshFingerprint != fingerprint || nodePoolMemo_->pools.size() != mesh.nodes.size()) {
    nodePoolMemo_->pools = findNodePools();
    nodePoolMemo_->meshFingerprint = fingerprint;
  }
  return nodePoolMemo_->pools;
}

std::vector<uint32_t> Solution::findNodePools() const {
  // Nodes at the same place on neighbouring patches of one smooth surface
  // form a pool (RadiosityMesh::sameSmoothSurface): the same material, and
  // either normals within 2° (a quad the input split in two, a floor
  // modelled as tiles, a finely tessellated model) or, where the model gives
  // vertex normals, shading normals within 2° (a low-poly smooth model whose
  // facets meet at 10–20° but share the vertex's normal). Creases (normals
  // further apart and no shared vertex normal) keep their jump.
  // Positions are matched on a grid of 10⁻⁶ of the scene's size: the two
  // patches computed their nodes with different arithmetic.
  std::vector<uint32_t> pool(mesh.nodes.size());
  for (uint32_t v = 0; v < pool.size(); ++v) pool[v] = v;
  double extent = 0;
  for (const Vec3 &p : mesh.nodes) extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  if (extent <= 0) return pool;
  const double cell = extent * 1e-6;
  // Nodes by grid cell, then by index: a sort, not a hash map of lists (one
  // allocation per node: seconds at the 2·10⁶ nodes of a 10⁶-triangle model).
  struct Keyed {
    int64_t x, y, z;
    uint32_t node;
    bool sameCell(const Keyed &o) const { return x == o.x && y == o.y && z == o.z; }
    bool operator<(const Keyed &o) const { return std::tie(x, y, z, node) < std::tie(o.x, o.y, o.z, o.node); }
  };
  std::vector<Keyed> keyed;
  keyed.reserve(mesh.nodes.size());
  for (uint32_t v = 0; v < mesh.nodes.size(); ++v) {
    // A node on a cut (the foot of a wall standing there) keeps its own patch's value.
    if (!mesh.nodeOnCut.empty() && mesh.nodeOnCut[v]) continue;
    const Vec3 &p = mesh.nodes[v];
    keyed.push_back({std::llround(p.x / cell), std::llround(p.y / cell), std::llround(p.z / cell), v});
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<uint32_t> nodes;
  std::vector<bool> used;
  for (size_t start = 0; start < keyed.size();) {
    size_t end = start + 1;
    while (end < keyed.size() && keyed[end].sameCell(keyed[start])) ++end;
    if (end - start >= 2) {
      nodes.clear();
      for (size_t i = start; i < end; ++i) nodes.push_back(keyed[i].node);
      // A pool: the nodes on one smooth surface with its first.
      used.assign(nodes.size(), false);
      for (size_t a = 0; a < nodes.size(); ++a) {
        if (used[a]) continue;
        for (size_t b = a + 1; b < nodes.size(); ++b) {
          if (!used[b] && mesh.sameSmoothSurface(nodes[a], nodes[b])) {
            used[b] = true;
            pool[nodes[b]] = nodes[a];
          }
        }
      }
    }
    start = end;
  }
  return pool;
}

void Solution::shareNodesAcrossPatches(std::vector<Bands> &sums, std::vector<double> &weight,
                                       const std::vector<uint32_t> &pool) const {
  // A pool's nodes share its sums, so the interpolated radiosity has no seam there.
  for (uint32_t v = 0; v < pool.size(); ++v)
    if (pool[v] != v) sums[pool[v]] += sums[v], weight[pool[v]] += weight[v];
  for (uint32_t v = 0; v < pool.size(); ++v)
    if (pool[v] != v) sums[v] = sums[pool[v]], weight[v] = weight[pool[v]];
}

std::vector<Bands> Solution::nodeValues(const std::vector<Bands> &perElement) const {
  return nodeValues(perElement, nodePools());
}

std::vector<Bands> Solution::nodeValues(const std::vector<Bands> &perElement,
                                        const std::vector<uint32_t> &pools) const {
  std::vector<double> weight(mesh.nodes.size(), 0.0);
  std::vector<Bands> values(mesh.nodes.size(), Bands(0.0));
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    for (int k = 0; k < element.vertexCount; ++k) {
      values[element.nodes[k]] += perElement[e] * element.area;
      weight[element.nodes[k]] += element.area;
    }
  }
  shareNodesAcrossPatches(values, weight, pools);
  for (size_t v = 0; v < values.size(); ++v)
    if (weight[v] > 0) values[v] = values[v] / weight[v];
  applyTVertices(values);
  return values;
}

void Solution::applyTVertices(std::vector<Bands> &values) const {
  for (const RadiosityMesh::TVertex &t : mesh.tVertices)
    values[t.node] = values[t.edgeStart] * (1.0 - t.t) + values[t.edgeEnd] * double(t.t);
}

void Solution::poolNodeIrradiance() {
  if (!hasNodeIrradiance()) return;
  // Only the pools of facets (some patch's normal more than 2° from the
  // first's: joined by their shading normals): in the others every node is
  // the same point on nearly the same plane, whose exact values already
  // agree to round-off, and they keep them.
  const std::vector<uint32_t> pools = nodePools();
  std::vector<uint8_t> facets(pools.size(), 0), pooled(pools.size(), 0);
  for (uint32_t v = 0; v < pools.size(); ++v)
    if (pools[v] != v && dot(mesh.patches[mesh.nodePatch[v]].normal, mesh.patches[mesh.nodePatch[pools[v]]].normal) <=
                             kSmoothSurfaceCosine)
      facets[pools[v]] = 1;
  for (uint32_t v = 0; v < pools.size(); ++v) pooled[v] = facets[pools[v]];
  bool any = false;
  for (uint8_t f : facets) any = any || f;
  if (!any) return;
  std::vector<double> area(mesh.nodes.size(), 0.0);
  for (const Element &element : mesh.elements)
    for (int k = 0; k < element.vertexCount; ++k) area[element.nodes[k]] += element.area;
  for (std::vector<Bands> *values : {&nodeDirectIrradiance, &nodeIndirectIrradiance}) {
    std::vector<Bands> sums(values->size());
    std::vector<double> weight = area;
    for (size_t v = 0; v < sums.size(); ++v) sums[v] = (*values)[v] * area[v];
    shareNodesAcrossPatches(sums, weight, pools);
    for (size_t v = 0; v < sums.size(); ++v)
      if (pooled[v] && weight[v] > 0) (*values)[v] = sums[v] / weight[v];
  }
}

void Solution::updateNodesAndErrors() {
  const bool atNodes = hasNodeIrradiance();
  std::vector<Bands> display(mesh.elements.size());
  for (uint32_t e = 0; e < mesh.elements.size(); ++e)
    display[e] = atNodes ? emission[e] + (reflectance[e] + transmittanceOf(e)) * ambient : displayRadiosity(e);
  // The pools once for every field (a sort of the nodes: 0.3 s at 2·10⁶).
  const std::vector<uint32_t> pools = nodePools();
  nodeRadiosity = nodeValues(display, pools);
  nodeReflectance = nodeValues(reflectance, pools);
  if (atNodes) {
    // The reflected part from the values computed at the nodes, ρ̄H there;
    // T-vertices again from their edges' ends, so the sum does not crack.
    std::vector<Bands> reflected(mesh.nodes.size());
    for (size_t v = 0; v < mesh.nodes.size(); ++v)
      reflected[v] = nodeReflectance[v] * (nodeDirectIrradiance[v] + nodeIndirectIrradiance[v]);
    applyTVertices(reflected);
    for (size_t v = 0; v < mesh.nodes.size(); ++v) nodeRadiosity[v] += reflected[v];
    // Light through translucent faces: computed per element, shown at the nodes like B.
    if (hasTransmitted()) {
      std::vector<Bands> through(elementCount());
      for (size_t e = 0; e < elementCount(); ++e) through[e] = transmittedDirect[e] + transmittedIndirect[e];
      const std::vector<Bands> atNode = nodeValues(through, pools);
      for (size_t v = 0; v < mesh.nodes.size(); ++v) nodeRadiosity[v] += atNode[v];
    }
  }
  // Gradient estimate (C&W ch. 6, Cohen et al. 1986): how far the nodes around
  // an element stray from its own value, relative to it. Large where the
  // constant element misrepresents a shadow edge or a steep falloff.
  errorEstimate.assign(mesh.elements.size(), 0.0);
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    const Element &element = mesh.elements[e];
    double b = displayRadiosity(e).luminance();
    double worst = 0;
    for (int k = 0; k < element.vertexCount; ++k)
      worst = std::max(worst, std::abs(nodeRadiosity[element.nodes[k]].luminance() - b));
    errorEstimate[e] = b > 0 ? worst / b : (worst > 0 ? 1.0 : 0.0);
  }
}

std::vector<Bands> Solution::nodeIndirectRadiosity() const {
  if (!hasNodeIrradiance()) {
    std::vector<Bands> indirectPerElement(elementCount());
    for (uint32_t e = 0; e < elementCount(); ++e)
      indirectPerElement[e] = indirect[e] + reflectance[e] * indirectAmbient;
    return nodeValues(indirectPerElement);
  }
  std::vector<Bands> values(mesh.nodes.size());
  for (size_t v = 0; v < mesh.nodes.size(); ++v) values[v] = nodeReflectance[v] * nodeIndirectIrradiance[v];
  applyTVertices(values);
  if (hasTransmitted()) {
    const std::vector<Bands> through = nodeValues(transmittedIndirect);
    for (size_t v = 0; v < values.size(); ++v) values[v] += through[v];
  }
  return values;
}

std::vector<Bands> Solution::nodeDirectRadiosity() const {
  if (!hasNodeIrradiance()) return nodeValues(direct);
  std::vector<Bands> values(mesh.nodes.size());
  for (size_t v = 0; v < mesh.nodes.size(); ++v) values[v] = nodeReflectance[v] * nodeDirectIrradiance[v];
  applyTVertices(values);
  if (hasTransmitted()) {
    const std::vector<Bands> through = nodeValues(transmittedDirect);
    for (size_t v = 0; v < values.size(); ++v) values[v] += through[v];
  }
  return values;
}

}  // namespace radiant
