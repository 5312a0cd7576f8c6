// ReflectedLightHierarchy: the clusters' part — links with a cluster at one
// end or both, their oracle, and the gather, push and pull through the
// clusters (reflected_light_hierarchy.h says what the whole does).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "radiosity/reflected_light_hierarchy.h"

namespace radiant {

void ReflectedLightHierarchy::initialiseClusters() {
  const size_t count = clusters_.clusters.size();
  clusterReflectance_.assign(count, Bands(kLeastReflectance));
  clusterReflected_.assign(count, Bands(0.0));
  clusterLargest_.assign(count, Bands(0.0));
  clusterIntensity_.assign(count, HarmonicBands{});
  clusterArea_.assign(count, HarmonicBands{});
  clusterField_.assign(count, HarmonicBands{});
  clusterFieldBelow_.assign(count, HarmonicBands{});
  clusterLinks_.assign(count, {});
  exactOffset_.assign(count, -1);
  patchClusterIrradiance_.assign(mesh_.patches.size(), Bands(0.0));
  int64_t exactTotal = 0;
  // Children follow their parents: from the back, a cluster's children are done before it.
  for (size_t i = count; i-- > 0;) {
    const Cluster &c = clusters_.clusters[i];
    for (uint32_t k = c.first; k < c.first + c.ownCount; ++k) {
      const uint32_t p = clusters_.order[k];
      const uint32_t root = static_cast<uint32_t>(mesh_.patches[p].treeRoot);
      for (int b = 0; b < kBandCount; ++b)
        clusterReflectance_[i][b] = std::max(clusterReflectance_[i][b], scattering(root)[b]);
      clusterArea_[i].addLobe(mesh_.patches[p].normal, Bands(mesh_.patches[p].area));
    }
    for (int32_t child : {c.left, c.right}) {
      if (child < 0) continue;
      for (int b = 0; b < kBandCount; ++b)
        clusterReflectance_[i][b] = std::max(clusterReflectance_[i][b], clusterReflectance_[child][b]);
      clusterArea_[i] += clusterArea_[child];
    }
    if (c.count <= kExactClusterPatches) {
      exactOffset_[i] = exactTotal;
      exactTotal += c.count;
    }
  }
  exactIrradiance_.assign(size_t(exactTotal), Bands(0.0));
}

bool ReflectedLightHierarchy::canSplitEnd(uint32_t id) const {
  if (!isCluster(id)) return canSplit(id);
  const Box3 &b = clusters_.clusters[clusterIndex(id)].bounds;
  return std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z}) >= 2 * minimumEdge_;
}

HierarchyEnd ReflectedLightHierarchy::hierarchyEnd(uint32_t id) const {
  if (!isCluster(id)) return HierarchyEnd::of(mesh_.tree[id], normalOf(id));
  const uint32_t c = clusterIndex(id);
  HierarchyEnd e = HierarchyEnd::of(clusters_.clusters[c]);
  e.patches =
      std::span<const uint32_t>(clusters_.order.data() + clusters_.clusters[c].first, clusters_.clusters[c].count);
  e.mesh = &mesh_;
  if (exactOffset_[c] < 0) e.areaHarmonics = &clusterArea_[c];
  return e;
}

void ReflectedLightHierarchy::childrenOf(uint32_t id, std::vector<uint32_t> &out) {
  out.clear();
  if (!isCluster(id)) {
    splitNode(id);
    for (int c = 0; c < 4; ++c) out.push_back(static_cast<uint32_t>(mesh_.tree[id].children[c]));
    return;
  }
  const Cluster &c = clusters_.clusters[clusterIndex(id)];
  for (uint32_t k = c.first; k < c.first + c.ownCount; ++k)
    out.push_back(static_cast<uint32_t>(mesh_.patches[clusters_.order[k]].treeRoot));
  if (c.hasChildren()) {
    out.push_back(clusterId(static_cast<uint32_t>(c.left)));
    out.push_back(clusterId(static_cast<uint32_t>(c.right)));
  }
}

bool ReflectedLightHierarchy::facingEnds(uint32_t a, uint32_t b) const {
  if (!isCluster(a) && !isCluster(b)) return facing(a, b);
  if (isCluster(a) && isCluster(b)) return true;
  // Some corner of the cluster's box in front of the node's plane.
  const uint32_t node = isCluster(a) ? b : a;
  const Box3 &box = clusters_.clusters[clusterIndex(isCluster(a) ? a : b)].bounds;
  const MeshTreeNode &t = mesh_.tree[node];
  const Vec3 &n = normalOf(node);
  const double tolerance = 1e-9 * std::sqrt(t.area);
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z};
    if (dot(corner - t.corners[0], n) > tolerance) return true;
  }
  return false;
}

Bands ReflectedLightHierarchy::intensity(uint32_t source, const Vec3 &w) const {
  if (!isCluster(source)) {
    const double c = dot(normalOf(source), w);
    return c > 0 ? reflected_[source] * (mesh_.tree[source].area * c * kInvPi) : Bands(0.0);
  }
  const uint32_t ci = clusterIndex(source);
  const Cluster &c = clusters_.clusters[ci];
  if (exactOffset_[ci] < 0) return clusterIntensity_[ci].value(w) * kInvPi;
  Bands sum(0.0);
  for (uint32_t k = c.first; k < c.first + c.count; ++k) {
    const Patch &p = mesh_.patches[clusters_.order[k]];
    const double cosine = dot(p.normal, w);
    if (cosine > 0) sum += reflected_[static_cast<uint32_t>(p.treeRoot)] * (p.area * cosine);
  }
  return sum * kInvPi;
}

double ReflectedLightHierarchy::projectedArea(uint32_t source, const Vec3 &w) const {
  if (!isCluster(source)) return mesh_.tree[source].area * std::max(0.0, dot(normalOf(source), w));
  const uint32_t ci = clusterIndex(source);
  const Cluster &c = clusters_.clusters[ci];
  if (exactOffset_[ci] < 0) return clusterArea_[ci].value(w)[0];
  double sum = 0;
  for (uint32_t k = c.first; k < c.first + c.count; ++k) {
    const Patch &p = mesh_.patches[clusters_.order[k]];
    sum += p.area * std::max(0.0, dot(p.normal, w));
  }
  return sum;
}

Bands ReflectedLightHierarchy::largestReflected(uint32_t id) const {
  if (isCluster(id)) return clusterLargest_[clusterIndex(id)];
  // The node's R polynomial at its corners (it is bilinear or linear: its largest is at one).
  const MeshTreeNode &t = mesh_.tree[id];
  static constexpr double quadCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  static constexpr double triangleCorner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  Bands largest = reflected_[id];
  for (int k = 0; k < t.vertexCount; ++k) {
    const auto &uv = t.vertexCount == 4 ? quadCorner[k] : triangleCorner[k];
    const Bands v = sourceShape_[id].value(uv[0], uv[1]);
    for (int b = 0; b < kBandCount; ++b) largest[b] = std::max(largest[b], v[b]);
  }
  return largest;
}

Bands ReflectedLightHierarchy::meanReflected(uint32_t id) const {
  return isCluster(id) ? clusterReflected_[clusterIndex(id)] : reflected_[id];
}

namespace {

/// How much the sampled visibility may be off: the smaller of the seen and
/// hidden fractions where the rays disagreed, and where they all agreed
/// what one more ray could have changed.
double visibilityUncertainty(double visibility, int rays) {
  if (visibility > 0 && visibility < 1) return std::min(visibility, 1 - visibility);
  // All blocked: the link is dropped, so what it may carry is lost, one
  // way only; all clear: one more ray could have found half blocked.
  return (visibility <= 0 ? 1.0 : 0.5) / std::max(rays, 1);
}

}  // namespace

double ReflectedLightHierarchy::clusterLinkError(uint32_t r, uint32_t s, const ClusterLinkEstimate &e) const {
  // F: the link's form factor (unoccluded): the source's projected area
  // toward the receiver over π times the kernel's mean, or the mean itself
  // in the near field.
  const double unoccluded = e.isotropic ? e.kernelMean : projectedArea(s, e.direction) * kInvPi * e.kernelMean;
  const double visible = unoccluded * e.visibility;
  const bool harmonics = !e.isotropic && ((isCluster(s) && exactOffset_[clusterIndex(s)] < 0) ||
                                          (isCluster(r) && exactOffset_[clusterIndex(r)] < 0));
  const Bands largest = largestReflected(s), mean = meanReflected(s);
  // The kernel holds the source's patches for a uniform R; how far R strays
  // from that over them: its largest against its mean (a node: how far its
  // polynomial misses its children).
  const Bands spreadOfR = isCluster(s) ? largest - mean : variation_[s];
  const Bands rho = isCluster(r) ? clusterReflectance_[clusterIndex(r)] : scattering(r);
  // The kernel's spread is over the receiver: splitting the source cannot
  // make it smaller, only spread it over more links (each under the
  // threshold, all together no better). A receiver that cannot be split
  // keeps it, whatever the source.
  const double spread = canSplitEnd(r) ? e.spread : 0.0;
  const double geometry = unoccluded * (spread + visibilityUncertainty(e.visibility, e.rays));
  double worst = 0;
  for (int b = 0; b < kBandCount; ++b) {
    const double err = geometry * largest[b] + visible * (spreadOfR[b] + (harmonics ? kHarmonicsError * mean[b] : 0.0));
    worst = std::max(worst, std::max(rho[b], kLeastReflectance) * err);
  }
  return worst;
}

double ReflectedLightHierarchy::clusterLinkError(const ClusterLinkRecord &l) const {
  ClusterLinkEstimate e;
  e.direction = l.directionVector();
  e.kernelMean = l.kernelMean;
  e.spread = l.spread;
  e.visibility = l.visibility;
  e.rays = l.rays;
  e.isotropic = l.nearField;
  return clusterLinkError(l.receiver, l.source, e);
}

void ReflectedLightHierarchy::keepClusterLink(uint32_t r, uint32_t s, const ClusterLinkEstimate &e, bool nearField) {
  ClusterLinkRecord record;
  record.receiver = r;
  record.source = s;
  // A point model close up can make a form factor above 1, which would
  // create light: no link carries more than all of its source's exitance.
  const double formFactor = e.isotropic ? e.kernelMean : projectedArea(s, e.direction) * kInvPi * e.kernelMean;
  const double scale = formFactor > 1 ? 1 / formFactor : 1.0;
  for (int k = 0; k < 4; ++k) record.kernel.c[k] = float(e.kernel.c[k] * scale);
  record.direction = {float(e.direction.x), float(e.direction.y), float(e.direction.z)};
  record.kernelMean = float(e.kernelMean);
  record.spread = float(std::min(e.spread, 1e30));
  record.visibility = float(e.visibility);
  record.rays = static_cast<uint8_t>(std::min(e.rays, 255));
  record.nearField = nearField;
  const uint32_t index = static_cast<uint32_t>(clusterRecords_.size());
  clusterRecords_.push_back(record);
  if (isCluster(r))
    clusterLinks_[clusterIndex(r)].push_back(index);
  else
    links_[r].push_back(index | kClusterBit);
}

void ReflectedLightHierarchy::gatherCluster(uint32_t c) {
  const Cluster &cluster = clusters_.clusters[c];
  const int64_t offset = exactOffset_[c];
  if (offset >= 0) std::fill_n(exactIrradiance_.begin() + offset, cluster.count, Bands(0.0));
  HarmonicBands field;
  for (uint32_t l : clusterLinks_[c]) {
    const ClusterLinkRecord &link = clusterRecords_[l];
    const Vec3 w = link.directionVector();
    if (link.nearField) {
      // The same irradiance on every surface: R̄ times the mean factor.
      const Bands e = meanReflected(link.source) * double(link.kernel.c[0]);
      if (offset < 0)
        field.addIsotropic(e);
      else
        for (uint32_t k = 0; k < cluster.count; ++k) exactIrradiance_[size_t(offset) + k] += e;
      continue;
    }
    // Irradiance on a surface facing the source: its intensity toward here, × V/d².
    const Bands e = intensity(link.source, w) * double(link.kernel.c[0]);
    if (offset < 0) {
      field.addDelta(-w, e);
      continue;
    }
    for (uint32_t k = 0; k < cluster.count; ++k) {
      const double cosine = -dot(mesh_.patches[clusters_.order[cluster.first + k]].normal, w);
      if (cosine > 0) exactIrradiance_[size_t(offset) + k] += e * cosine;
    }
  }
  clusterField_[c] = field;
}

void ReflectedLightHierarchy::pushClusters() {
  const size_t count = clusters_.clusters.size();
  for (size_t c = 0; c < count; ++c) {
    clusterFieldBelow_[c] = clusterField_[c];
    const int32_t parent = clusters_.clusters[c].parent;
    if (parent >= 0) clusterFieldBelow_[c] += clusterFieldBelow_[parent];
  }
  tbb::parallel_for(size_t(0), mesh_.patches.size(), [&](size_t p) {
    int32_t c = static_cast<int32_t>(clusters_.ownerOf[p]);
    Bands e = clusterFieldBelow_[c].irradiance(mesh_.patches[p].normal);
    // The small clusters above the patch (its owner and up) gathered it patch by patch.
    for (; c >= 0 && exactOffset_[c] >= 0; c = clusters_.clusters[c].parent)
      e += exactIrradiance_[size_t(exactOffset_[c]) + clusters_.positionOf[p] - clusters_.clusters[c].first];
    patchClusterIrradiance_[p] = e;
  });
}

void ReflectedLightHierarchy::pullClusters() {
  for (size_t i = clusters_.clusters.size(); i-- > 0;) {
    const Cluster &c = clusters_.clusters[i];
    Bands sum(0.0), largest(0.0);
    HarmonicBands intensity;
    for (uint32_t k = c.first; k < c.first + c.ownCount; ++k) {
      const Patch &p = mesh_.patches[clusters_.order[k]];
      const uint32_t root = static_cast<uint32_t>(p.treeRoot);
      sum += reflected_[root] * p.area;
      const Bands top = largestReflected(root);
      for (int b = 0; b < kBandCount; ++b) largest[b] = std::max(largest[b], top[b]);
      if (exactOffset_[i] < 0) intensity.addLobe(p.normal, reflected_[root] * p.area);
    }
    for (int32_t child : {c.left, c.right}) {
      if (child < 0) continue;
      sum += clusterReflected_[child] * clusters_.clusters[child].area;
      for (int b = 0; b < kBandCount; ++b) largest[b] = std::max(largest[b], clusterLargest_[child][b]);
      if (exactOffset_[i] < 0) {
        // A small child has no harmonics of its own: its patches' lobes, once.
        if (exactOffset_[child] >= 0) {
          const Cluster &small = clusters_.clusters[child];
          for (uint32_t k = small.first; k < small.first + small.count; ++k) {
            const Patch &p = mesh_.patches[clusters_.order[k]];
            intensity.addLobe(p.normal, reflected_[static_cast<uint32_t>(p.treeRoot)] * p.area);
          }
        } else {
          intensity += clusterIntensity_[child];
        }
      }
    }
    clusterReflected_[i] = c.area > 0 ? sum / c.area : Bands(0.0);
    clusterLargest_[i] = largest;
    clusterIntensity_[i] = intensity;
  }
}

}  // namespace radiant
