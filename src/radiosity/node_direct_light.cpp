#include "radiosity/node_direct_light.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

#include "cluster/cluster.h"
#include "radiosity/backprojection.h"
#include "util/phase.h"
#include "util/sampling.h"

namespace radiant {

namespace {

/// Evaluates f(i) → Bands for i < count, each on one MPI rank (i mod N), in
/// parallel, and sums the ranks' results: every rank gets every value, and
/// x + 0 = x keeps them bit for bit one process's. Reported as the phase
/// `phaseName` (util/phase.h: a bar with an ETA on the command line).
template <typename F>
std::vector<Bands> evaluateSplit(const char *phaseName, size_t count, int threads, const F &f) {
  Phase phase(phaseName, count);
  const size_t ranks = size_t(cluster::size()), rank = size_t(cluster::rank());
  std::vector<double> values(count * kBandCount, 0.0);
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), count, [&](size_t i) {
      phase.advance();
      if (i % ranks != rank) return;
      const Bands h = f(i);
      for (int b = 0; b < kBandCount; ++b) values[i * kBandCount + b] = h[b];
    });
  });
  cluster::sumOnAllRanks(values.data(), values.size());
  std::vector<Bands> result(count);
  for (size_t i = 0; i < count; ++i)
    for (int b = 0; b < kBandCount; ++b) result[i][b] = values[i * kBandCount + b];
  return result;
}

/// The distance from `centre` to the nearest light, emitter polygons taken
/// as balls about their centroids: the scale over which the direct light varies.
double nearestLight(const Scene &scene, const DirectIrradiance &direct, const Vec3 &centre) {
  double nearest = INFINITY;
  for (const PointLight &light : scene.lights)
    nearest = std::min(nearest, std::max(length(light.position - centre) - light.halfLength, 0.0));
  for (const EmitterPolygon &e : direct.emitters()) {
    const std::span<const Vec3> corners(e.corners.data(), size_t(e.vertexCount));
    const Vec3 c = polygonCentroid(corners);
    double radius = 0;
    for (const Vec3 &p : corners) radius = std::max(radius, length(p - c));
    nearest = std::min(nearest, std::max(length(c - centre) - radius, 0.0));
  }
  return nearest;
}

}  // namespace

MeshDirectLight directLightOfMesh(const RayTracer &tracer, const Solution &solution, int threads,
                                  size_t maxExactOccluders) {
  const RadiosityMesh &mesh = solution.mesh;
  const Scene &scene = tracer.scene();
  const DirectIrradiance direct(scene, tracer, maxExactOccluders);
  MeshDirectLight light;
  light.atNodes.assign(mesh.nodes.size(), Bands(0.0));
  light.ofElements.assign(mesh.elements.size(), Bands(0.0));
  if (direct.empty() || mesh.nodes.empty()) return light;

  // At the nodes: one evaluation per pool, with the mean of its patches'
  // normals (the smooth surface the facets stand for), shared by all of them.
  // Also for a pool joined by its shading normals (a low-poly model's
  // vertex, RadiosityMesh::nodeShadingNormals), not the shading normal
  // itself: the facets' mean is what the pool's elements receive light
  // over, and what the reflected light's gather (reflected_light_gather.cpp)
  // looks along, so direct and reflected light at a node keep one direction.
  const std::vector<uint32_t> pool = solution.nodePools();
  std::vector<Vec3> normalSum(mesh.nodes.size());
  for (uint32_t v = 0; v < pool.size(); ++v) normalSum[pool[v]] += mesh.patches[mesh.nodePatch[v]].normal;
  // The meshing may have evaluated some already (direct_light_mesh.h).
  auto knownAt = [](const std::vector<Bands> &known, size_t i) { return i < known.size() && !std::isnan(known[i][0]); };
  std::vector<uint32_t> heads;
  for (uint32_t v = 0; v < pool.size(); ++v)
    if (pool[v] == v) {
      if (knownAt(solution.knownNodeDirect, v))
        light.atNodes[v] = solution.knownNodeDirect[v];
      else
        heads.push_back(v);
    }
  const std::vector<Bands> atHeads = evaluateSplit("direct light at the nodes", heads.size(), threads, [&](size_t i) {
    const uint32_t v = heads[i];
    const Patch &patch = mesh.patches[mesh.nodePatch[v]];
    // A node on the patch's boundary may lie in the plane of a wall that
    // stands there; the light it receives is the limit from inside the
    // patch, so evaluate a hair's breadth towards the patch's interior
    // (as DirectLightField::evaluate does).
    Vec3 centre;
    for (int k = 0; k < patch.vertexCount; ++k) centre += patch.corners[k];
    centre = centre / patch.vertexCount;
    const Vec3 x = mesh.nodes[v] + (centre - mesh.nodes[v]) * 1e-7;
    const double len = length(normalSum[v]);
    return direct.irradiance(x, len > 0 ? normalSum[v] / len : patch.normal);
  });
  for (size_t i = 0; i < heads.size(); ++i) light.atNodes[heads[i]] = atHeads[i];
  for (uint32_t v = 0; v < pool.size(); ++v) light.atNodes[v] = light.atNodes[pool[v]];
  // A T-vertex takes its edge's interpolation, as every node field does, so
  // the display does not crack there.
  for (const RadiosityMesh::TVertex &t : mesh.tVertices)
    light.atNodes[t.node] = light.atNodes[t.edgeStart] * (1.0 - t.t) + light.atNodes[t.edgeEnd] * double(t.t);

  // Over the elements: the corners' mean where the element is tiny against
  // the distance over which the light varies (its error is then of order
  // (size/distance)², far below the rays' noise), a lattice elsewhere.
  constexpr double kTiny = 0.1;  // 4·size/distance below this: the corners
  std::vector<uint32_t> large;
  std::vector<int> lattice(mesh.elements.size(), 0);
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    if (knownAt(solution.knownElementDirect, e)) {
      light.ofElements[e] = solution.knownElementDirect[e];
      continue;
    }
    const Element &element = mesh.elements[e];
    double size = 0;
    for (int k = 0; k < element.vertexCount; ++k)
      size = std::max(size,
                      length(mesh.nodes[element.nodes[(k + 1) % element.vertexCount]] - mesh.nodes[element.nodes[k]]));
    const double nearest = nearestLight(scene, direct, element.centre);
    const double ratio = 4.0 * size / std::max(nearest, 1e-9 * size);
    if (ratio <= kTiny) {
      for (int k = 0; k < element.vertexCount; ++k) light.ofElements[e] += light.atNodes[element.nodes[k]];
      light.ofElements[e] = light.ofElements[e] / double(element.vertexCount);
    } else {
      lattice[e] = int(std::clamp(std::ceil(ratio), 3.0, 16.0));  // clamped first: ratio reaches 4·10⁹ beside a light
      large.push_back(e);
    }
  }
  const std::vector<Bands> means =
      evaluateSplit("direct light over the elements", large.size(), threads, [&](size_t i) {
        const uint32_t e = large[i];
        // The midpoint rule, as meanPointLightIrradiance, with every light.
        const std::vector<Vec3> polygon = mesh.polygon(e);
        const Vec3 &normal = mesh.normalOf(e);
        return latticeMean(polygon, lattice[e], [&](const Vec3 &x) { return direct.irradiance(x, normal); });
      });
  for (size_t i = 0; i < large.size(); ++i) light.ofElements[large[i]] = means[i];
  return light;
}

}  // namespace radiant
