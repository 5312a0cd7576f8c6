// The hemicube (Cohen & Greenberg 1985; Cohen & Wallace ch. 4).
//
// A cube of half-width 1 at unit height over the point: the top face z = 1,
// (x, y) ∈ [−1,1]², and four half side faces such as y = 1, x ∈ [−1,1],
// z ∈ [0,1]. A pixel of area ΔA centred at its coordinates carries the delta
// form factor
//     top face : ΔF = ΔA / (π (x² + y² + 1)²)
//     side face: ΔF = z ΔA / (π (x² + z² + 1)²)     (z: height above the base)
// (the formulas of S. E. Chen's rad.c, Graphics Gems II). The factor from the
// point to a patch is the sum of ΔF over the pixels whose nearest surface it
// is. The table is used as computed (midpoint rule, Σ ΔF = 1 + O(1/res²)), not
// renormalised, so its totals are the midpoint-rule sums (1.000530 at res 32;
// docs/radiosity.md, Form factors).
//
// Resolution: pixels across the full top face, rounded up to even so the side
// faces split evenly; rad.c's room example uses 100. The per-patch error is
// dominated by pixels straddling a patch's outline, O(1/res) per patch; random
// rotation about the normal (rad.c) turns that aliasing into noise.
#include "radiosity/hemicube.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace radiant {

Hemicube::Hemicube(int resolution) : resolution_(std::max(2, resolution + (resolution & 1))) {
  const int res = resolution_;
  const double pixel = 2.0 / res;  // pixel edge; ΔA = pixel²
  const double deltaArea = pixel * pixel;
  pixels_.reserve(static_cast<size_t>(res) * res + 4 * static_cast<size_t>(res) * (res / 2));

  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      const double x = -1 + (i + 0.5) * pixel, y = -1 + (j + 0.5) * pixel;
      const double d = x * x + y * y + 1;
      const double deltaF = deltaArea / (kPi * d * d);
      pixels_.push_back({{x, y, 1}, deltaF});
      top_ += deltaF;
    }

  // The four side faces share one table of (s, z, ΔF), s along the face. Each
  // face is stored contiguously so that a chunk of rays stays coherent.
  std::vector<Pixel> side;
  side.reserve(static_cast<size_t>(res) * (res / 2));
  for (int j = 0; j < res / 2; ++j)
    for (int i = 0; i < res; ++i) {
      const double s = -1 + (i + 0.5) * pixel, z = (j + 0.5) * pixel;
      const double d = s * s + z * z + 1;
      const double deltaF = z * deltaArea / (kPi * d * d);
      side_ += deltaF;
      side.push_back({{s, 1, z}, deltaF});  // the face y = +1
    }
  // The other three by quarter turns about the normal: (x, y) → (y, −x).
  for (int turn = 0; turn < 4; ++turn)
    for (Pixel &entry : side) {
      pixels_.push_back(entry);
      entry.direction = {entry.direction.y, -entry.direction.x, entry.direction.z};
    }
}

double Hemicube::totalDeltaFormFactor() const {
  return top_ + 4 * side_;
}
double Hemicube::topFaceDeltaFormFactor() const {
  return top_;
}
double Hemicube::sideFaceDeltaFormFactor() const {
  return side_;
}

double Hemicube::gather(const RayTracer &tracer, const Vec3 &p, const Vec3 &n,
                        const std::function<int(const Hit &)> &target, std::vector<double> &formFactors, Pcg32 &rng,
                        bool randomRotation) const {
  const Vec3 normal = normalize(n);
  const Frame frame = Frame::fromNormal(normal);
  Vec3 tangent = frame.tangent, bitangent = frame.bitangent;
  if (randomRotation) {
    const double angle = 2 * kPi * rng.next();
    const double c = std::cos(angle), s = std::sin(angle);
    tangent = frame.tangent * c + frame.bitangent * s;
    bitangent = frame.bitangent * c - frame.tangent * s;
  }

  // Embree's stream query in chunks of neighbouring pixels (coherent rays).
  constexpr size_t kChunk = 1024;
  std::vector<Ray> rays(std::min(kChunk, pixels_.size()));
  std::vector<Hit> hits(rays.size());
  std::vector<uint8_t> found(rays.size());
  double escaped = 0;
  for (size_t start = 0; start < pixels_.size(); start += kChunk) {
    const size_t count = std::min(kChunk, pixels_.size() - start);
    for (size_t k = 0; k < count; ++k) {
      const Vec3 &d = pixels_[start + k].direction;
      rays[k] = tracer.spawnRay(p, normal, normalize(tangent * d.x + bitangent * d.y + normal * d.z));
    }
    tracer.intersectMany(std::span<const Ray>(rays.data(), count), std::span<Hit>(hits.data(), count),
                         std::span<uint8_t>(found.data(), count));
    for (size_t k = 0; k < count; ++k) {
      const double deltaF = pixels_[start + k].deltaFormFactor;
      if (!found[k]) {
        escaped += deltaF;
        continue;
      }
      const int index = target(hits[k]);
      if (index < 0) continue;
      if (static_cast<size_t>(index) >= formFactors.size())
        throw std::out_of_range("Hemicube::gather: target index beyond the form-factor vector");
      formFactors[static_cast<size_t>(index)] += deltaF;
    }
  }
  return escaped;
}

}  // namespace radiant
