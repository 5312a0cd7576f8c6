#include "radiosity/hierarchical_link.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "radiosity/form_factor.h"
#include "util/sampling.h"

namespace radiant {

namespace {

/// The point of a link end at parameters (u, v) in [0,1]² (bilinear, or Heitz's map on triangles).
Vec3 pointOnLinkEnd(const HierarchicalLinkEnd &n, double u, double v) {
  const auto &c = n.corners;
  if (n.vertexCount == 4)
    return c[0] * ((1 - u) * (1 - v)) + c[1] * (u * (1 - v)) + c[2] * (u * v) + c[3] * ((1 - u) * v);
  double b1, b2;
  sampleUniformTriangle(u, v, b1, b2);
  return c[0] * (1 - b1 - b2) + c[1] * b1 + c[2] * b2;
}

}  // namespace

// Plain area-weighted visibility halved the Cornell back wall's factor to the
// floor, whose far half hides behind the tall block while its near half is in
// plain view: the near parts of a source dominate its form factor, so each
// shadow ray is weighted by the kernel it stands for.
LinkMeasure measureHierarchicalLink(const RayTracer &tracer, const HierarchicalLinkEnd &receiver,
                                    const HierarchicalLinkEnd &source, int visibilitySamples, Pcg32 rng) {
  const int m = std::max(4, static_cast<int>(std::lround(std::sqrt(double(visibilitySamples)))));
  // Receiver points and source strata are paired by a random permutation:
  // a fixed pairing (row j of the receiver always with row j of the source)
  // correlates where the receiver looks with where it looks from, and
  // halved the back wall's factor to the floor in the Cornell box.
  std::vector<int> strata(size_t(m) * m);
  for (int k = 0; k < m * m; ++k) strata[k] = k;
  for (int k = m * m - 1; k > 0; --k) std::swap(strata[k], strata[static_cast<int>(rng.next() * (k + 1))]);
  double unoccluded = 0, weightVisible = 0, weightAll = 0;
  const double pieceArea = source.area / (m * m);
  int visible = 0, tested = 0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      Vec3 x = pointOnLinkEnd(receiver, (i + 0.5) / m, (j + 0.5) / m);
      int stratum = strata[i * m + j];
      double su = (stratum % m + rng.next()) / m, sv = (stratum / m + rng.next()) / m;
      if (dot(x - source.centre, source.normal) <= 0) continue;  // behind the source's front
      double f = formFactorPointToPolygon(x, receiver.normal,
                                          std::span<const Vec3>(source.corners.data(), size_t(source.vertexCount)));
      if (f <= 0) continue;
      unoccluded += f;
      // The form factor counts only the part of the source in front of x's
      // tangent plane, so visibility must be sampled there too: a point
      // behind it (a floor point under a block, seen from the block's side)
      // would always read as occluded. Retry a few times before giving up.
      Vec3 y = pointOnLinkEnd(source, su, sv);
      for (int retry = 0; retry < 8 && dot(y - x, receiver.normal) <= 0; ++retry)
        y = pointOnLinkEnd(source, rng.next(), rng.next());
      Vec3 d = y - x;
      double r2 = dot(d, d), r = std::sqrt(r2);
      double cosX = dot(d, receiver.normal) / r, cosY = -dot(d, source.normal) / r;
      if (cosX <= 0 || cosY <= 0) continue;
      double weight = cosX * cosY / (kPi * r2 + pieceArea);
      ++tested;
      weightAll += weight;
      if (tracer.visible(x, receiver.normal, y, source.normal)) {
        weightVisible += weight;
        ++visible;
      }
    }
  LinkMeasure l;
  l.unoccludedFormFactor = unoccluded / (m * m);
  // No ray could be aimed (every grid point saw the source edge-on): no
  // evidence of occlusion, so keep the unoccluded factor, which is tiny then.
  l.formFactor = weightAll > 0 ? l.unoccludedFormFactor * weightVisible / weightAll : l.unoccludedFormFactor;
  l.shadowRays = uint32_t(tested);
  l.arrived = uint32_t(visible);
  return l;
}

}  // namespace radiant
