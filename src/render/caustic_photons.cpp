#include "render/caustic_photons.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/bsdf.h"
#include "render/light_sampler.h"
#include "util/random.h"
#include "util/sampling.h"

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

CausticPhotonMap::CausticPhotonMap(const RayTracer &tracer, size_t emitted, uint64_t seed, double radius,
                                   bool throughDiffuse)
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
      Vec3 direction;
      Bands power;
      Ray ray;
      if (light.pointLight) {
        // A point light: a direction by its distribution, power = I(ω) / (p(ω) p(light) N).
        double pdf = 0;
        direction = light.pointLight->sampleDirection(rng.next(), rng.next(), pdf);
        if (!(pdf > 0)) continue;
        power = light.pointLight->intensity(direction) * (1.0 / (pdf * light.probability * double(emitted)));
        ray = tracer.spawnRay(light.position, direction, direction);  // ε off the point: a ceiling it is set in
      } else {
        // Cosine-distributed direction: power = L·cos/(p_A · cos/π) / N = π L / (p_A N).
        direction = Frame::fromNormal(light.normal).toWorld(sampleCosineHemisphere(rng.next(), rng.next()));
        power = light.radiance * (kPi / (light.pdfArea * double(emitted)));
        ray = tracer.spawnRay(light.position, light.normal, direction);
      }
      bool afterSpecular = false;
      for (int bounce = 0; bounce <= kMaxSpecularBounces; ++bounce) {
        Hit hit;
        if (!tracer.intersect(ray, hit)) break;
        const Material &material = scene.materials[hit.material];
        const Vec3 wo = -ray.direction;
        if (!material.isDelta()) {
          // L S+ D: stored only after a specular bounce (otherwise it is direct light).
          // Rough glass ends the photon unstored: the path tracer follows
          // light through it itself (it is no delta bounce), and no one reads the map there.
          if (afterSpecular && !material.isSpecular())
            stored[c].push_back(
                {hit.position, dot(wo, hit.geometricNormal) >= 0 ? hit.geometricNormal : -hit.geometricNormal, power});
          if (!throughDiffuse) break;
        }
        afterSpecular = material.isDelta() || (throughDiffuse && afterSpecular);
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

void CausticPhotonMap::cellOf(const Vec3 &p, int64_t cell[3]) const {
  for (int k = 0; k < 3; ++k) cell[k] = int64_t(std::floor(p[k] / cellSize_));
}

uint64_t CausticPhotonMap::cellKey(int64_t x, int64_t y, int64_t z) {
  // 21 bits per axis: 2 million cells along each side of the scene. Cells
  // further apart share a key, which costs only distance tests.
  constexpr uint64_t mask = (uint64_t(1) << 21) - 1;
  return (uint64_t(x) & mask) | (uint64_t(y) & mask) << 21 | (uint64_t(z) & mask) << 42;
}

namespace {

constexpr int kOccupancyBits = 18;  // 32 KiB: stays in each core's cache

}  // namespace

void CausticPhotonMap::buildGrid() {
  // Each photon is listed in the cells (side 2r) its sphere of radius r
  // reaches: two per axis, the one holding p − r and the next (taken
  // exactly, not from p + r, whose rounding could name a third), so a
  // lookup reads one cell only.
  cellSize_ = 2 * radius_;
  if (photons_.size() > (size_t(1) << 28))  // 8 listings each must fit the table's 32-bit ranges
    throw std::length_error("caustic photon map: more than 2^28 photons stored");
  std::vector<std::pair<uint64_t, uint32_t>> keyed;
  keyed.reserve(photons_.size() * 8);
  for (uint32_t i = 0; i < photons_.size(); ++i) {
    int64_t lo[3];
    cellOf(photons_[i].position - Vec3(radius_, radius_, radius_), lo);
    uint64_t keys[8];
    int count = 0;
    for (int corner = 0; corner < 8; ++corner) {
      // Cells 2 million apart share a key: list the photon there once.
      const uint64_t key = cellKey(lo[0] + (corner & 1), lo[1] + (corner >> 1 & 1), lo[2] + (corner >> 2 & 1));
      if (std::find(keys, keys + count, key) != keys + count) continue;
      keys[count++] = key;
      keyed.push_back({key, i});
    }
  }
  std::sort(keyed.begin(), keyed.end());
  size_t cells = 0;
  for (size_t i = 0; i < keyed.size(); ++i) cells += i == 0 || keyed[i].first != keyed[i - 1].first;
  size_t capacity = 16;
  while (capacity < 2 * cells) capacity *= 2;  // load ≤ 1/2: short probe sequences
  table_.assign(capacity, Slot{});
  occupied_.assign((size_t(1) << kOccupancyBits) / 64, 0);
  cellPhotons_.resize(keyed.size());
  for (size_t k = 0; k < keyed.size(); ++k) {
    const CausticPhoton &photon = photons_[keyed[k].second];
    GridPhoton &g = cellPhotons_[k];
    g.position = photon.position;
    for (int a = 0; a < 3; ++a) g.normal[a] = float(photon.normal[a]);
    for (int b = 0; b < kBandCount; ++b) g.power[b] = float(photon.power[b]);
  }
  for (uint32_t i = 0; i < keyed.size();) {
    uint32_t j = i;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    const uint64_t hash = mixBits(keyed[i].first);
    size_t slot = hash & (capacity - 1);
    while (table_[slot].key != kEmptyKey) slot = (slot + 1) & (capacity - 1);
    table_[slot] = {keyed[i].first, i, j};
    const uint64_t bit = hash >> (64 - kOccupancyBits);
    occupied_[bit / 64] |= uint64_t(1) << (bit % 64);
    i = j;
  }
}

std::pair<uint32_t, uint32_t> CausticPhotonMap::cellRange(uint64_t key) const {
  const uint64_t hash = mixBits(key), bit = hash >> (64 - kOccupancyBits);
  if (!(occupied_[bit / 64] >> (bit % 64) & 1)) return {0, 0};
  for (size_t slot = hash & (table_.size() - 1);; slot = (slot + 1) & (table_.size() - 1)) {
    if (table_[slot].key == key) return {table_[slot].first, table_[slot].last};
    if (table_[slot].key == kEmptyKey) return {0, 0};
  }
}

Bands CausticPhotonMap::irradiance(const Vec3 &position, const Vec3 &normal) const {
  Bands sum(0.0);
  if (photons_.empty()) return sum;
  int64_t cell[3];
  cellOf(position, cell);
  const auto [first, last] = cellRange(cellKey(cell[0], cell[1], cell[2]));
  const double r2 = radius_ * radius_, slab = 0.25 * radius_;
  const float nx = float(normal.x), ny = float(normal.y), nz = float(normal.z);
  double power[kBandCount] = {};  // a cell in a bright caustic sums thousands
  for (uint32_t k = first; k < last; ++k) {
    const GridPhoton &photon = cellPhotons_[k];
    // In double: a scene far from the origin must not lose the disc to rounding.
    const Vec3 d = photon.position - position;
    // Same surface: within the disc, and arrived on the side this normal faces.
    if (dot(d, d) <= r2 && photon.normal[0] * nx + photon.normal[1] * ny + photon.normal[2] * nz > 0.5f &&
        std::abs(dot(d, normal)) < slab)
      for (int b = 0; b < kBandCount; ++b) power[b] += photon.power[b];
  }
  for (int b = 0; b < kBandCount; ++b) sum[b] = power[b];
  return sum / (kPi * radius_ * radius_);
}

Bands CausticPhotonMap::reflectedRadiance(const Vec3 &position, const Vec3 &normal, const Bands &rho) const {
  return rho * irradiance(position, normal) * kInvPi;
}

}  // namespace radiant
