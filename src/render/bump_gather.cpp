#include "render/bump_gather.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

#include "radiosity/solution_query.h"
#include "util/error.h"
#include "util/random.h"

namespace radiant {

namespace {

/// Radiance the solution shows along a gather ray: B/π of the front of the
/// diffuse surface it meets (emission included), 0 for anything else. The
/// point's texture is not applied: the ratio is formed from a thousand rays,
/// over which the element's mean ρ̄ (what B̂ holds) is the texture's average,
/// and ρ(y) texel by texel would only add noise to it.
Bands incidentRadiance(const RayTracer &tracer, const Solution &solution, const Ray &ray, bool reflectedOnly) {
  Hit hit;
  SolutionPoint at;
  if (!tracer.intersect(ray, hit) || !locateHit(solution, hit, -ray.direction, at)) return Bands(0.0);
  return (reflectedOnly ? reflectedRadiosity(solution, at) : radiosity(solution, at)) * kInvPi;
}

}  // namespace

const ParameterSpec &bumpOrientationsParameter() {
  static const ParameterSpec spec = [] {
    ParameterSpec s = {"bump-orientations",
                       ParameterType::Integer,
                       "16",
                       "normal orientations gathered per node of a bump-mapped surface, an even number (two tilts × "
                       "azimuths; Chen & Wu 1990)",
                       4,
                       64};
    s.multipleOf = BumpGather::kTilts;  // refused when the command line is read, not after the solve
    return s;
  }();
  return spec;
}

int bumpOrientations(const Parameters &parameters) {
  return int(parameters.integer("bump-orientations"));
}

BumpGather::BumpGather(const RayTracer &tracer, const Solution &solution, const BumpGatherOptions &options)
    : solution_(solution) {
  if (options.orientations < 2 * kTilts || options.orientations % kTilts != 0 || options.rays < 1)
    throw std::invalid_argument("BumpGather: orientations must be an even number ≥ 4, rays ≥ 1");
  azimuths_ = options.orientations / kTilts;
  const Scene &scene = tracer.scene();
  const RadiosityMesh &mesh = solution.mesh;
  std::vector<uint32_t> gathered;
  nodeTable_.assign(mesh.nodes.size(), -1);
  for (uint32_t v = 0; v < mesh.nodes.size(); ++v) {
    const Material &m = scene.materials[mesh.patches[mesh.nodePatch[v]].material];
    if (m.bumpTextureIndex < 0 && m.normalTextureIndex < 0) continue;
    nodeTable_[v] = int32_t(gathered.size());
    gathered.push_back(v);
  }
  if (gathered.empty()) {
    nodeTable_.clear();
    return;
  }
  const int perNode = kTilts * azimuths_;
  ratios_.assign(gathered.size() * perNode * kBandCount, 1.0f);
  // Stratified uniform directions over the hemisphere (cos θ and φ uniform):
  // every tilted normal re-weights the same samples by max(0, n'·ω).
  const int strata = std::max(1, int(std::sqrt(double(options.rays))));
  tbb::parallel_for(size_t(0), gathered.size(), [&](size_t g) {
    const uint32_t v = gathered[g];
    const Patch &patch = mesh.patches[mesh.nodePatch[v]];
    const Vec3 n = patch.normal;
    const Frame frame = Frame::fromNormal(n);
    // From a node on the patch's rim, rays along a neighbouring wall would
    // slip through the corner: gather from 1 % of the way towards the patch's centre, at most 1 mm.
    Vec3 centre;
    for (int k = 0; k < patch.vertexCount; ++k) centre += patch.corners[k] / double(patch.vertexCount);
    const double towards = length(centre - mesh.nodes[v]);
    const Vec3 origin = mesh.nodes[v] + (centre - mesh.nodes[v]) * (towards > 0 ? std::min(0.01, 1e-3 / towards) : 0.0);
    std::vector<Vec3> tilted;
    for (int t = 0; t < kTilts; ++t)
      for (int a = 0; a < azimuths_; ++a) {
        const double theta = (t + 1) * kTiltStepDegrees * kPi / 180, phi = 2 * kPi * a / azimuths_;
        tilted.push_back({std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
      }
    Pcg32 rng(options.seed, v);  // per node: the same table whatever the thread count
    Bands flat(0.0);
    std::vector<Bands> sums(perNode, Bands(0.0));
    for (int i = 0; i < strata; ++i)
      for (int j = 0; j < strata; ++j) {
        const double cosTheta = (i + rng.next()) / strata, phi = 2 * kPi * (j + rng.next()) / strata;
        const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
        const Vec3 local{sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
        const Bands L =
            incidentRadiance(tracer, solution, tracer.spawnRay(origin, n, frame.toWorld(local)), options.reflectedOnly);
        if (L.max() <= 0) continue;
        flat += L * cosTheta;
        for (int k = 0; k < perNode; ++k) sums[k] += L * std::max(0.0, dot(tilted[k], local));
      }
    // Point lights are no surfaces a ray can meet: their direct light enters
    // exactly, scaled as the sums are (the sums estimate E·N/2π from N
    // uniform directions). Not for reflected light only (shirley, kok sample them per pixel).
    if (!options.reflectedOnly)
      for (const PointLight &light : tracer.scene().lights)
        for (int p = 0; p < light.latticePointCount(); ++p) {
          const Vec3 at = light.latticePoint(p), toLight = at - origin;
          const double distance2 = dot(toLight, toLight);
          if (!(distance2 > 0)) continue;
          const Vec3 w = toLight / std::sqrt(distance2), local = frame.toLocal(w);
          if (local.z <= 0 || !tracer.seesPoint(origin, n, at)) continue;
          const Bands scaled =
              light.intensity(-w) * (double(strata * strata) / (2 * kPi * distance2 * light.latticePointCount()));
          flat += scaled * local.z;
          for (int k = 0; k < perNode; ++k) sums[k] += scaled * std::max(0.0, dot(tilted[k], local));
        }
    // Directions of a tilted normal's hemisphere below the node's horizon
    // bring nothing, as in the path tracer (a shading normal never lets light
    // through the geometric surface): in a furnace r(θ') = (1 + cos θ')/2.
    for (int k = 0; k < perNode; ++k)
      for (int b = 0; b < kBandCount; ++b)
        ratios_[(g * perNode + k) * kBandCount + b] = float(flat[b] > 0 ? sums[k][b] / flat[b] : 1.0);
  });
}

Bands BumpGather::nodeRatio(uint32_t node, const Vec3 &bumpedNormal) const {
  if (nodeTable_.empty() || nodeTable_[node] < 0) return Bands(1.0);
  const float *table = &ratios_[size_t(nodeTable_[node]) * kTilts * azimuths_ * kBandCount];
  const Vec3 local =
      Frame::fromNormal(solution_.mesh.patches[solution_.mesh.nodePatch[node]].normal).toLocal(bumpedNormal);
  // Tilt levels at 0 (the flat normal, ratio 1), 30° and 60°, interpolated in
  // 1 − cos θ', in which a uniform field's ratio (1 + cos θ')/2 is linear;
  // clamped at the last level. Azimuth: linear, wrapping.
  auto level = [](double cosTheta) { return 1 - cosTheta; };
  const double c = std::clamp(local.z, -1.0, 1.0);
  double tilt = kTilts;
  for (int t = 1; t <= kTilts; ++t) {
    const double lo = level(std::cos((t - 1) * kTiltStepDegrees * kPi / 180)),
                 hi = level(std::cos(t * kTiltStepDegrees * kPi / 180));
    if (level(c) <= hi) {
      tilt = (t - 1) + (level(c) - lo) / (hi - lo);
      break;
    }
  }
  double azimuth = std::atan2(local.y, local.x) / (2 * kPi) * azimuths_;
  if (azimuth < 0) azimuth += azimuths_;
  const int a0 = int(azimuth) % azimuths_, a1 = (a0 + 1) % azimuths_;
  const double fa = azimuth - std::floor(azimuth);
  auto atTilt = [&](int t) {  // t ≥ 1
    const float *row = table + size_t(t - 1) * azimuths_ * kBandCount;
    Bands r;
    for (int b = 0; b < kBandCount; ++b) r[b] = row[a0 * kBandCount + b] * (1 - fa) + row[a1 * kBandCount + b] * fa;
    return r;
  };
  const int t0 = std::min(int(tilt), kTilts - 1);
  const double ft = tilt - t0;
  const Bands lower = t0 == 0 ? Bands(1.0) : atTilt(t0);
  return lower * (1 - ft) + atTilt(t0 + 1) * ft;
}

Bands BumpGather::ratio(const MeshLocation &location, const Vec3 &bumpedNormal, const Vec3 &unbumpedNormal) const {
  if (nodeTable_.empty()) return Bands(1.0);
  const Element &e = solution_.mesh.elements[location.element];
  // Rodrigues: the smallest rotation taking the unbumped normal a to the patch normal b, applied to n'.
  const Vec3 a = unbumpedNormal, b = solution_.mesh.patches[e.patch].normal;
  const double c = dot(a, b);
  const Vec3 k = cross(a, b);
  const double s2 = dot(k, k);
  Vec3 n = bumpedNormal;
  if (s2 > 1e-24 && c > -0.999)
    n = normalize(bumpedNormal * c + cross(k, bumpedNormal) + k * (dot(k, bumpedNormal) * (1 - c) / s2));
  const std::array<double, 4> w = solution_.mesh.nodeWeights(location);
  Bands r(0.0);
  for (int j = 0; j < e.vertexCount; ++j) r += w[j] * nodeRatio(e.nodes[j], n);
  return r;
}

}  // namespace radiant
