#include "radiosity/cluster_link_estimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "radiosity/form_factor.h"

namespace radiant {

namespace {

int extremePoints(const HierarchyEnd &end, Vec3 *out) {
  if (end.node) {
    for (int k = 0; k < end.node->vertexCount; ++k) out[k] = end.node->corners[k];
    return end.node->vertexCount;
  }
  const Box3 &b = end.bounds;
  for (int k = 0; k < 8; ++k) out[k] = {k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z};
  return 8;
}

/// The point kernel between a receiver point p and a source point q:
/// cosines at the ends that are surfaces, over d².
double pointKernel(const HierarchyEnd &receiver, const Vec3 &p, const HierarchyEnd &source, const Vec3 &q) {
  const Vec3 d = q - p;
  const double d2 = dot(d, d);
  if (!(d2 > 0)) return 0;
  double g = 1 / d2;
  const double distance = std::sqrt(d2);
  if (receiver.node) g *= std::max(0.0, dot(receiver.normal, d) / distance);
  if (source.node) g *= std::max(0.0, -dot(source.normal, d) / distance);
  return g;
}

Vec3 pointOnNode(const MeshTreeNode &n, double u, double v) {
  if (n.vertexCount == 4)
    return n.corners[0] * ((1 - u) * (1 - v)) + n.corners[1] * (u * (1 - v)) + n.corners[2] * (u * v) +
           n.corners[3] * ((1 - u) * v);
  return n.corners[0] * (1 - u - v) + n.corners[1] * u + n.corners[2] * v;
}

/// Up to kEstimatePatches of a cluster's patches, evenly spaced through
/// its range, each standing for its share of the cluster's area.
constexpr size_t kEstimatePatches = 32;

struct PatchSet {
  std::vector<const Patch *> patches;
  std::vector<Vec3> centroids;
  double weight = 1;  ///< the cluster's area over the sampled patches'
};

Vec3 centroidOf(const Patch &p) {
  Vec3 c;
  for (int k = 0; k < p.vertexCount; ++k) c += p.corners[k];
  return c / double(p.vertexCount);
}

void samplePatches(const HierarchyEnd &end, PatchSet &out, size_t most) {
  out.patches.clear();
  out.centroids.clear();
  out.weight = 1;
  const size_t count = end.patches.size();
  if (count == 0) return;
  const size_t taken = std::min(count, most);
  double sampled = 0, total = 0;
  for (size_t k = 0; k < taken; ++k) {
    const Patch &p = end.mesh->patches[end.patches[(2 * k + 1) * count / (2 * taken)]];
    out.patches.push_back(&p);
    out.centroids.push_back(centroidOf(p));
    sampled += p.area;
  }
  if (taken < count) {
    total = end.cluster->area;
    out.weight = sampled > 0 ? total / sampled : 1.0;
  }
}

/// Σ_j F(x, n → patch j), exact per patch (Lambert), over the patches
/// whose front x lies in front of.
/// `perPatch`, when given, accumulates each patch's term times `weight`.
double formFactorToPatches(const Vec3 &x, const Vec3 &n, const PatchSet &set, double *perPatch = nullptr,
                           double weight = 1) {
  double f = 0;
  for (size_t k = 0; k < set.patches.size(); ++k) {
    const Patch *p = set.patches[k];
    const Vec3 d = set.centroids[k] - x;
    const double d2 = dot(d, d), from = -dot(d, p->normal);
    if (from <= 0) continue;  // x is behind its front
    // Far from it (over 4 of its sizes away), the patch is a point to 0.5 %;
    // close by, Lambert's contour integral.
    double term;
    if (d2 > 16 * p->area)
      term = p->area * std::max(0.0, dot(d, n)) * from / (kPi * d2 * d2);
    else if (dot(x - p->corners[0], p->normal) <= 0)
      continue;
    else
      term = formFactorPointToPolygon(x, n, std::span<const Vec3>(p->corners.data(), size_t(p->vertexCount)));
    f += term;
    if (perPatch) perPatch[k] += term * weight;
  }
  return f * set.weight;
}

/// A pair of points a visibility ray may join, with the share of the
/// link's light that passes between them.
struct RayCandidate {
  Vec3 from, fromNormal, to, toNormal;
  double weight = 0;
};

bool facesEachOther(const Vec3 &a, const Vec3 &na, const Vec3 &b, const Vec3 &nb) {
  return dot(b - a, na) > 0 && dot(a - b, nb) > 0;
}

/// A ray between a point (`point`, normal `pointNormal`) and one of a
/// node's interior points, the first from `start` on that faces it both
/// ways (a ray from a point the other faces away from would only find its
/// own surface); none facing: no candidate. `nodeIsSource` orders the ends.
void addCandidate(const MeshTreeNode &node, const Vec3 &nodeNormal, const Vec3 &point, const Vec3 &pointNormal,
                  size_t start, double weight, bool nodeIsSource, std::vector<RayCandidate> &out) {
  static constexpr double quadAt[4][2] = {{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  static constexpr double triangleAt[4][2] = {
      {1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}, {1.0 / 3, 1.0 / 3}};
  for (size_t t = 0; t < 4; ++t) {
    const auto &uv = node.vertexCount == 4 ? quadAt[(start + t) % 4] : triangleAt[(start + t) % 4];
    const Vec3 y = pointOnNode(node, uv[0], uv[1]);
    if (!facesEachOther(y, nodeNormal, point, pointNormal)) continue;
    if (nodeIsSource)
      out.push_back({point, pointNormal, y, nodeNormal, weight});
    else
      out.push_back({y, nodeNormal, point, pointNormal, weight});
    return;
  }
}

/// The fraction of the link's light that arrives: rays between candidates
/// chosen in proportion to their shares (at evenly spaced quantiles, so the
/// same pairs every time), which makes the fraction consistent with the
/// kernel: a patch that carries much of the light is tested, one seen at
/// grazing that carries little rarely is. Where all four are blocked, eight
/// more, before the link is dropped: what a dropped link carried is only
/// ever lost, so those losses would add up.
double sampledVisibility(const RayTracer &tracer, const std::vector<RayCandidate> &candidates, int &rays) {
  double total = 0;
  for (const RayCandidate &c : candidates) total += c.weight;
  rays = 0;
  if (!(total > 0)) return 1;
  int seen = 0;
  auto castAt = [&](double quantile) {
    double target = quantile * total, running = 0;
    for (const RayCandidate &c : candidates) {
      running += c.weight;
      if (running < target || !(c.weight > 0)) continue;
      ++rays;
      seen += tracer.visible(c.from, c.fromNormal, c.to, c.toNormal);
      return;
    }
  };
  for (int k = 0; k < 4; ++k) castAt((k + 0.5) / 4);
  if (seen == 0)
    for (int k = 0; k < 8; ++k) castAt((k + 0.5) / 8 + (k % 2 ? 0.03 : -0.03));
  return rays > 0 ? double(seen) / rays : 1.0;
}

}  // namespace

HierarchyEnd HierarchyEnd::of(const MeshTreeNode &n, const Vec3 &normal) {
  HierarchyEnd e;
  e.node = &n;
  e.normal = normal;
  Vec3 c;
  for (int k = 0; k < n.vertexCount; ++k) e.bounds.extend(n.corners[k]), c += n.corners[k];
  e.centre = c / double(n.vertexCount);
  return e;
}

HierarchyEnd HierarchyEnd::of(const Cluster &c) {
  HierarchyEnd e;
  e.cluster = &c;
  e.bounds = c.bounds;
  e.centre = c.centre;
  return e;
}

double HierarchyEnd::projectedArea(const Vec3 &w) const {
  if (node) return node->area * std::max(0.0, dot(normal, w));
  if (areaHarmonics) return areaHarmonics->value(w)[0];
  double a = 0;
  for (uint32_t p : patches) a += mesh->patches[p].area * std::max(0.0, dot(mesh->patches[p].normal, w));
  return a;
}

bool endsOverlap(const HierarchyEnd &a, const HierarchyEnd &b) {
  // Boxes that only touch count: a model standing on a floor is no point seen from it.
  return a.bounds.overlaps(b.bounds, 0.0);
}

ClusterLinkEstimate estimateClusterLink(const RayTracer &tracer, const HierarchyEnd &receiver,
                                        const HierarchyEnd &source, bool nearField) {
  ClusterLinkEstimate e;
  e.isotropic = nearField;
  const Vec3 d = receiver.centre - source.centre;
  const double distance = length(d);
  e.direction = distance > 0 ? d / distance : Vec3(0, 0, 1);
  // A cluster's patches one by one (a sample of them for a large one):
  // exact in their shapes, distances and orientations.
  thread_local PatchSet sourcePatches, receiverPatches;
  sourcePatches.patches.clear();
  receiverPatches.patches.clear();
  const size_t perSide = receiver.node ? kEstimatePatches : kEstimatePatches / 2;
  thread_local std::vector<RayCandidate> candidates;
  candidates.clear();
  if (source.cluster) samplePatches(source, sourcePatches, perSide);
  if (receiver.cluster) samplePatches(receiver, receiverPatches, perSide);

  if (receiver.node) {
    // At the receiver's cubature points, F(x → the source's patches) per
    // unit R: as it is for the near field (R̄ times it is the light); for a
    // link, over the source's projected area toward the receiver, so that
    // the source's intensity that way times it is the light, weighted by
    // the patches that face the receiver.
    const MeshTreeNode &n = *receiver.node;
    const bool quad = n.vertexCount == 4;
    const std::vector<CubaturePoint> &rule = receiverRule(quad);
    double values[9] = {}, sum = 0;
    thread_local std::vector<double> share;
    share.assign(sourcePatches.patches.size(), 0.0);
    for (size_t k = 0; k < rule.size(); ++k) {
      values[k] = formFactorToPatches(pointOnNode(n, rule[k].u, rule[k].v), receiver.normal, sourcePatches,
                                      share.data(), rule[k].weight);
      sum += rule[k].weight * values[k];
    }
    // Rays from the receiver's interior points to the patches that light it.
    for (size_t j = 0; j < share.size(); ++j)
      if (share[j] > 0)
        addCandidate(n, receiver.normal, sourcePatches.centroids[j], sourcePatches.patches[j]->normal, j, share[j],
                     false, candidates);
    // The intensity toward the receiver covers the patches facing that
    // way; where none do and yet the receiver sees some (a wide source
    // close by), the link carries the source's mean R instead.
    const double projected = source.projectedArea(e.direction);
    if (!nearField && !(projected > 0) && sum > 0) e.isotropic = true;
    const double scale = e.isotropic ? 1.0 : kPi / projected;
    for (size_t k = 0; k < rule.size(); ++k) values[k] *= scale;
    e.kernelMean = sum * scale;
    e.kernel = fitReceiverPolynomial(quad, std::span<const double>(values, rule.size()));
    // What the polynomial misses of the kernel, relative to its mean.
    double misfit = 0;
    for (size_t k = 0; k < rule.size(); ++k)
      misfit = std::max(misfit, std::abs(values[k] - e.kernel.value(rule[k].u, rule[k].v)));
    e.spread = e.kernelMean > 0 ? misfit / e.kernelMean : 0.0;
  } else {
    // A cluster receiver: each of its surfaces takes the irradiance from
    // the direction the light travels with its own cosine. From a polygon,
    // that direction is −Γ̂, Γ the polygon's vector form factor at the
    // cluster's centre, which makes n_i·Γ exact in the source's shape and
    // the surfaces' orientations; from a cluster, the centres' direction.
    // The kernel is then scaled so that the receiver's surfaces take on
    // average what they would from exact point-to-patch factors. In the
    // near field every surface takes that average.
    if (source.node) {
      const MeshTreeNode &s = *source.node;
      const Vec3 gamma =
          vectorFormFactor(receiver.centre, std::span<const Vec3>(s.corners.data(), size_t(s.vertexCount)));
      const double magnitude = length(gamma);
      if (magnitude > 0) e.direction = -gamma / magnitude;
    }
    const double sourceProjected = source.projectedArea(e.direction);
    double exact = 0, cosine = 0, area = 0;
    thread_local std::vector<double> share;
    for (size_t k = 0; k < receiverPatches.patches.size(); ++k) {
      const Patch *p = receiverPatches.patches[k];
      const Vec3 &x = receiverPatches.centroids[k];
      double f;
      if (source.node) {
        const MeshTreeNode &s = *source.node;
        f = dot(x - s.corners[0], source.normal) > 0
                ? formFactorPointToPolygon(x, p->normal, std::span<const Vec3>(s.corners.data(), size_t(s.vertexCount)))
                : 0.0;
        // Rays to the source's interior points, in turn.
        if (f > 0) addCandidate(s, source.normal, x, p->normal, k, p->area * f, true, candidates);
      } else {
        share.assign(sourcePatches.patches.size(), 0.0);
        f = formFactorToPatches(x, p->normal, sourcePatches, share.data(), p->area);
        for (size_t j = 0; j < share.size(); ++j)
          if (share[j] > 0 &&
              facesEachOther(x, p->normal, sourcePatches.centroids[j], sourcePatches.patches[j]->normal))
            candidates.push_back(
                {x, p->normal, sourcePatches.centroids[j], sourcePatches.patches[j]->normal, share[j]});
      }
      exact += p->area * f;
      cosine += p->area * std::max(0.0, -dot(p->normal, e.direction));
      area += p->area;
    }
    // No surface of the sample faces the light's way, or the source shows
    // nothing that way, and yet some take light: the mean to every surface.
    if (!nearField && exact > 0 && !(cosine > 0 && sourceProjected > 0)) e.isotropic = true;
    e.kernelMean = e.isotropic ? (area > 0 ? exact / area : 0.0) : kPi * exact / (sourceProjected * cosine);
    e.kernel.c[0] = e.kernelMean;
    // Its surfaces all take the centre's distance: how far that is off at
    // the corners of its box, to first order.
    if (!nearField && !e.isotropic) {
      Vec3 corners[8];
      extremePoints(receiver, corners);
      const double centre = pointKernel(receiver, receiver.centre, source, source.centre);
      double deviation = 0, largest = 0;
      for (const Vec3 &c : corners) {
        const double g = pointKernel(receiver, c, source, source.centre);
        deviation = std::max(deviation, std::abs(g - centre));
        largest = std::max(largest, g);
      }
      e.spread = centre > 0 ? deviation / centre : (largest > 0 ? 1e30 : 0.0);
    }
  }
  if (nearField) e.spread = 0;  // nothing can be split: no estimate needed
  // Carried as the source's mean R: as far off as R strays, which the
  // oracle counts; and the receiver's surfaces all take the mean, which this
  // says may be off by all of it.
  else if (e.isotropic && receiver.cluster)
    e.spread = std::max(e.spread, 1.0);

  // Visibility, in proportion to the light each pair of points carries.
  if (e.kernelMean > 0) {
    e.visibility = sampledVisibility(tracer, candidates, e.rays);
    for (double &c : e.kernel.c) c *= e.visibility;
  }
  return e;
}

}  // namespace radiant
