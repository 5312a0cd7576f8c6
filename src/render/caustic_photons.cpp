#include "render/caustic_photons.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "render/bsdf.h"
#include "render/light_sampler.h"
#include "render/sampling.h"
#include "util/random.h"

namespace radiant {

namespace {

/// Photons are traced in chunks of this many, each chunk with its own
/// generator and output, concatenated in chunk order: the map depends only on the seed.
constexpr size_t kChunk = 4096;
constexpr int kMaxSpecularBounces = 64;

double sceneDiagonal(const Scene &scene) {
  if (scene.positions.empty()) return 1;
  Vec3 lo = scene.positions[0], hi = lo;
  for (const Vec3 &p : scene.positions)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  return std::max(1e-9, length(hi - lo));
}

}  // namespace

CausticPhotonMap::CausticPhotonMap(const RayTracer &tracer, size_t emitted, uint64_t seed, double radius)
    : emitted_(emitted) {
  const Scene &scene = tracer.scene();
  radius_ = radius > 0 ? radius : 0.01 * sceneDiagonal(scene);
  LightSampler lights(scene);
  if (lights.empty() || emitted == 0) return;
  const size_t chunks = (emitted + kChunk - 1) / kChunk;
  std::vector<std::vector<CausticPhoton>> stored(chunks);
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    Pcg32 rng(seed, 0x9e3779b97f4a7c15ULL ^ c);
    for (size_t i = c * kChunk; i < std::min(emitted, (c + 1) * kChunk); ++i) {
      LightSample light;
      if (!lights.sample(rng.next(), rng.next(), rng.next(), light)) continue;
      // Cosine-distributed direction: power = L·cos/(p_A · cos/π) / N = π L / (p_A N).
      const Vec3 direction = Frame::fromNormal(light.normal).toWorld(sampleCosineHemisphere(rng.next(), rng.next()));
      Bands power = light.radiance * (kPi / (light.pdfArea * double(emitted)));
      Ray ray = tracer.spawnRay(light.position, light.normal, direction);
      for (int bounce = 0; bounce <= kMaxSpecularBounces; ++bounce) {
        Hit hit;
        if (!tracer.intersect(ray, hit)) break;
        const Material &material = scene.materials[hit.material];
        const Vec3 wo = -ray.direction;
        if (!material.isDelta()) {
          // L S+ D: stored only after a specular bounce (otherwise it is direct light).
          if (bounce > 0)
            stored[c].push_back({hit.position, dot(wo, hit.geometricNormal) >= 0 ? hit.geometricNormal : -hit.geometricNormal, power});
          break;
        }
        Bsdf bsdf(material, hit.shadingNormal, hit.geometricNormal, wo);
        BsdfSample s;
        if (!bsdf.sample(rng.next(), rng.next(), rng.next(), s)) break;
        // Power, unlike radiance, is not scaled by (η_i/η_t)² across an
        // interface: undo the BSDF's radiance factor on refraction (review).
        Bands weight = s.weight;
        if (s.isTransmission) {
          const double eta = dot(wo, hit.geometricNormal) >= 0 ? material.ior : 1.0 / material.ior;
          weight *= eta * eta;
        }
        power *= weight;
        // Russian roulette on what a mirror or tinted glass absorbs: unbiased, and photons keep their power.
        const double survive = std::min(1.0, weight.max());
        if (survive < 1) {
          if (rng.next() >= survive) break;
          power *= 1.0 / survive;
        }
        ray = tracer.spawnRay(hit.position, hit.geometricNormal, s.wi);
      }
    }
  });
  for (auto &chunk : stored) photons_.insert(photons_.end(), chunk.begin(), chunk.end());
  buildGrid();
}

uint64_t CausticPhotonMap::cellKey(int64_t x, int64_t y, int64_t z) const {
  // A hash of the integer cell: collisions only cost extra distance tests.
  return (uint64_t(x) * 73856093ULL) ^ (uint64_t(y) * 19349663ULL) ^ (uint64_t(z) * 83492791ULL);
}

void CausticPhotonMap::buildGrid() {
  grid_.clear();
  grid_.reserve(photons_.size());
  for (uint32_t i = 0; i < photons_.size(); ++i) {
    const Vec3 &p = photons_[i].position;
    grid_.push_back({cellKey(int64_t(std::floor(p.x / radius_)), int64_t(std::floor(p.y / radius_)),
                             int64_t(std::floor(p.z / radius_))),
                     i});
  }
  std::sort(grid_.begin(), grid_.end());
  cells_.clear();
  for (uint32_t i = 0; i < grid_.size();) {
    uint32_t j = i;
    while (j < grid_.size() && grid_[j].first == grid_[i].first) ++j;
    cells_.emplace(grid_[i].first, std::make_pair(i, j));
    i = j;
  }
}

Bands CausticPhotonMap::irradiance(const Vec3 &position, const Vec3 &normal) const {
  Bands sum(0.0);
  if (photons_.empty()) return sum;
  const int64_t cx = int64_t(std::floor(position.x / radius_)), cy = int64_t(std::floor(position.y / radius_)),
                cz = int64_t(std::floor(position.z / radius_));
  const double r2 = radius_ * radius_;
  uint64_t seen[27];  // a hash collision may list one cell's photons twice
  int seenCount = 0;
  for (int64_t dx = -1; dx <= 1; ++dx)
    for (int64_t dy = -1; dy <= 1; ++dy)
      for (int64_t dz = -1; dz <= 1; ++dz) {
        const uint64_t key = cellKey(cx + dx, cy + dy, cz + dz);
        if (std::find(seen, seen + seenCount, key) != seen + seenCount) continue;
        seen[seenCount++] = key;
        const auto cell = cells_.find(key);
        if (cell == cells_.end()) continue;
        for (uint32_t k = cell->second.first; k < cell->second.second; ++k) {
          const CausticPhoton &photon = photons_[grid_[k].second];
          const Vec3 d = photon.position - position;
          // Same surface: within the disc, and arrived on the side this normal faces.
          if (dot(d, d) <= r2 && dot(photon.normal, normal) > 0.5 && std::abs(dot(d, normal)) < 0.25 * radius_)
            sum += photon.power;
        }
      }
  return sum / (kPi * r2);
}

Bands CausticPhotonMap::reflectedRadiance(const Vec3 &position, const Vec3 &normal, const Bands &rho) const {
  return rho * irradiance(position, normal) * kInvPi;
}

}  // namespace radiant
