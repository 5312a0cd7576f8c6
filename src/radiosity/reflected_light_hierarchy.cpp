// ReflectedLightHierarchy: the tree nodes' part and the solve. The
// refinement (linking, splitting, re-linking) is in
// reflected_light_refinement.cpp, the clusters' part in
// reflected_light_clusters.cpp; what the whole does is in
// reflected_light_hierarchy.h.
#include "radiosity/reflected_light_hierarchy.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>

#include "cluster/cluster.h"
#include "radiosity/transmission.h"
#include "raytrace/surface_detail.h"

namespace radiant {

namespace {

/// A leaf's gathered polynomial, restricted from a coarse link whose kernel
/// falls steeply over its receiver (a surface close to a cluster), can dip
/// below 0 at one end; irradiance cannot.
Bands nonNegative(Bands b) {
  for (int k = 0; k < kBandCount; ++k) b[k] = std::max(0.0, b[k]);
  return b;
}

}  // namespace

ReflectedLightHierarchy::ReflectedLightHierarchy(const Scene &scene, const RayTracer &tracer, RadiosityMesh &mesh,
                                                 DirectLightField &field, const SolverOptions &options,
                                                 double minimumEdge)
    : scene_(scene),
      tracer_(tracer),
      mesh_(mesh),
      field_(field),
      options_(options),
      faces_(scene),
      estimator_(scene, faces_, &tracer),
      clusters_(buildClusterTree(mesh)),
      minimumEdge_(minimumEdge),
      arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {
  for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
    addNodeData(n);
    leaves_ += mesh_.tree[n].isLeaf();
  }
  twinFace_.assign(mesh_.patches.size(), -1);
  for (uint32_t p = 0; p < mesh_.patches.size(); ++p) {
    if (transmittance_[size_t(mesh_.patches[p].treeRoot)].max() <= 0) continue;
    const int32_t twin = scene_.faces[mesh_.patches[p].face].twin;
    if (twin < 0 || mesh_.patchOfFace[size_t(twin)] < 0) continue;
    twinFace_[p] = twin;
    anyTranslucent_ = true;
  }
  initialiseClusters();
}

void ReflectedLightHierarchy::keepForTransmission() {
  if (!anyTranslucent_) return;
  directBefore_ = direct_;
  meanIrradianceBefore_ = meanIrradiance_;
}

std::pair<Bands, Bands> ReflectedLightHierarchy::transmitted(uint32_t leaf) const {
  const MeshTreeNode &t = mesh_.tree[leaf];
  const int32_t twin = twinFace_[t.patch];
  if (twin < 0) return {Bands(0.0), Bands(0.0)};
  Vec3 centre;
  for (int k = 0; k < t.vertexCount; ++k) centre += t.corners[k] / double(t.vertexCount);
  // The other side's patch under this leaf (a face cut on one side only has
  // pieces that differ), then its node over the same region.
  const int32_t other = mesh_.patchAt(uint32_t(twin), centre);
  if (other < 0) return {Bands(0.0), Bands(0.0)};
  const uint32_t root = uint32_t(mesh_.patches[size_t(other)].treeRoot);
  if (root >= directBefore_.size()) return {Bands(0.0), Bands(0.0)};
  // Nodes split since the last keepForTransmission have no kept values yet: their parents stand in.
  const uint32_t m =
      coveringNode(mesh_.tree, root, centre, mesh_.patches[size_t(other)].normal, t.area, directBefore_.size());
  return {transmittance_[leaf] * directBefore_[m], transmittance_[leaf] * meanIrradianceBefore_[m]};
}

Bands ReflectedLightHierarchy::scattering(uint32_t n) const {
  Bands s = reflectance_[n];
  for (int b = 0; b < kBandCount; ++b) s[b] = std::max(s[b], transmittance_[n][b]);
  return s;
}

void ReflectedLightHierarchy::addNodeData(uint32_t n) {
  const MeshTreeNode &t = mesh_.tree[n];
  const Patch &patch = mesh_.patches[t.patch];
  const Material &material = scene_.materials[patch.material];
  Bands rho = material.kind == MaterialKind::Lambertian || material.kind == MaterialKind::Glossy ? material.diffuse
                                                                                                 : Bands(0.0);
  if (material.diffuseTextureIndex >= 0 && rho.max() > 0)
    rho = averageDiffuse(scene_, patch.face, std::span<const Vec3>(t.corners.data(), size_t(t.vertexCount)));
  reflectance_.push_back(rho);
  transmittance_.push_back(material.kind == MaterialKind::Lambertian || material.kind == MaterialKind::Glossy
                               ? material.transmittance
                               : Bands(0.0));
  meanIrradiance_.push_back(Bands(0.0));
  emission_.push_back(material.emission * kPi);
  reflected_.push_back(Bands(0.0));
  sourceShape_.emplace_back();
  directShape_.emplace_back();
  gathered_.emplace_back();
  irradiance_.emplace_back();
  direct_.push_back(Bands(0.0));
  variation_.push_back(Bands(0.0));
  links_.emplace_back();
}

void ReflectedLightHierarchy::initialiseFromDirectLight() {
  std::vector<std::pair<uint32_t, Vec3>> points;
  std::vector<Vec3> nodePoints;
  for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
    if (!mesh_.tree[n].isLeaf()) continue;
    field_.testPointsOf(mesh_.tree[n], nodePoints);
    for (const Vec3 &p : nodePoints) points.push_back({mesh_.tree[n].patch, p});
  }
  field_.evaluate(mesh_, points, options_.threads);
  // The first linking judges links by the sources' R, which is not known
  // yet. ρ·H_direct alone leaves every shadowed source at 0, and a link
  // from it passes whatever its error; so start from the ambient estimate
  // of the reflected light too (Cohen, Chen, Wallace & Greenberg 1988):
  // the first bounce's area mean R₁ spread evenly and reflected again and
  // again, H_ambient = R₁ / (1 − ρ̄), ρ̄ the area-mean reflectance.
  Bands firstBounce(0.0), reflectance(0.0);
  double area = 0;
  // Twice with translucent faces: the second pass reads the other sides' direct light.
  for (int pass = 0; pass < (anyTranslucent_ ? 2 : 1); ++pass) {
    keepForTransmission();
    for (uint32_t p = 0; p < mesh_.patches.size(); ++p) pullDirect(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
  }
  keepForTransmission();
  for (uint32_t p = 0; p < mesh_.patches.size(); ++p) {
    const uint32_t root = static_cast<uint32_t>(mesh_.patches[p].treeRoot);
    firstBounce += reflected_[root] * mesh_.tree[root].area;
    reflectance += reflectance_[root] * mesh_.tree[root].area;
    area += mesh_.tree[root].area;
  }
  ReceiverPolynomial<Bands> ambient;
  if (area > 0)
    for (int b = 0; b < kBandCount; ++b)
      ambient.c[0][b] = firstBounce[b] / area / (1 - std::min(reflectance[b] / area, 0.95));
  for (uint32_t p = 0; p < mesh_.patches.size(); ++p) {
    double change = 0, largest = 0;
    pushPull(static_cast<uint32_t>(mesh_.patches[p].treeRoot), ambient, change, largest);
    pullShapes(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
  }
  pullClusters();
}

void ReflectedLightHierarchy::updateVariation() {
  // Only the refinement reads it, so it is taken before each, not every
  // sweep. It holds through a refinement: a split makes children that are
  // exact restrictions of their parent's polynomial, which leaves the
  // parent's variation as it was (and a new leaf's is 0).
  arena_.execute([&] {
    tbb::parallel_for(uint32_t(0), uint32_t(mesh_.tree.size()),
                      [&](uint32_t n) { variation_[n] = computeVariation(n); });
  });
}

void ReflectedLightHierarchy::gatherAll() {
  // Every node and cluster gathers over its links (each rank its own
  // receivers: the sweeps' largest part, which every rank repeated), and
  // what the clusters gathered goes down to their patches (patchClusterIrradiance_).
  arena_.execute([&] {
    tbb::parallel_for(uint32_t(0), uint32_t(mesh_.tree.size()), [&](uint32_t n) {
      if (ownsReceiver(n)) gatherTreeNode(n);
    });
    tbb::parallel_for(uint32_t(0), uint32_t(clusters_.clusters.size()), [&](uint32_t c) {
      if (ownsReceiver(clusterId(c))) gatherCluster(c);
    });
  });
  if (cluster::distributed()) shareGathered();
  arena_.execute([&] { pushClusters(); });
}

void ReflectedLightHierarchy::shareGathered() {
  auto indices = [](size_t count) {
    std::vector<size_t> all(count);
    for (size_t i = 0; i < count; ++i) all[i] = i;
    return all;
  };
  cluster::shareOwnedEntries(gathered_, indices(gathered_.size()), [&](size_t n) { return ownsReceiver(uint32_t(n)); });
  cluster::shareOwnedEntries(clusterField_, indices(clusterField_.size()),
                             [&](size_t c) { return ownsReceiver(clusterId(uint32_t(c))); });
  // A small cluster's slice of exactIrradiance_, one entry per patch of its range.
  std::vector<size_t> exact;
  std::vector<uint8_t> owned(exactIrradiance_.size(), 0);
  for (uint32_t c = 0; c < clusters_.clusters.size(); ++c) {
    if (exactOffset_[c] < 0) continue;
    const bool mine = ownsReceiver(clusterId(c));
    for (uint32_t k = 0; k < clusters_.clusters[c].count; ++k) {
      exact.push_back(size_t(exactOffset_[c]) + k);
      owned[size_t(exactOffset_[c]) + k] = mine ? 1 : 0;
    }
  }
  cluster::shareOwnedEntries(exactIrradiance_, exact, [&](size_t i) { return owned[i] != 0; });
}

void ReflectedLightHierarchy::measureClosure() {
  // The form factors from any point sum to at most 1 (they share its
  // hemisphere, Cohen & Wallace §2.5), so a leaf whose links sum past 1
  // counts some light twice: a cluster link's kernel taken at a point of the
  // receiving cluster that sees more than its other patches do, say a small
  // patch of a sphere where it touches the floor. The sweeps then grow there
  // by ρ·ΣF > 1 and never settle. One gather of R = 1 measures ΣF at every
  // leaf; the leaf's gathered light is then scaled by 1/ΣF where it passes
  // 1 by more than the estimates' own error (a few per cent, either way:
  // clipping those would take light out of a closed box).
  constexpr double kClosureSlack = 1.25;
  const auto reflected = reflected_;
  const auto shapes = sourceShape_;
  const uint32_t nodes = static_cast<uint32_t>(mesh_.tree.size());
  for (uint32_t n = 0; n < nodes; ++n) {
    reflected_[n] = Bands(1.0);
    sourceShape_[n] = ReceiverPolynomial<Bands>();
    sourceShape_[n].c[0] = Bands(1.0);
  }
  pullClusters();
  closure_.assign(nodes, 1.0f);
  gatherAll();
  arena_.execute([&] {
    tbb::parallel_for(size_t(0), mesh_.patches.size(), [&](size_t p) {
      auto walk = [&](auto &self, uint32_t n, ReceiverPolynomial<Bands> down) -> void {
        const MeshTreeNode &t = mesh_.tree[n];
        down += gathered_[n];
        if (t.isLeaf()) {
          const double sum = down.mean(t.vertexCount == 4).average();
          if (sum > kClosureSlack) closure_[n] = float(1 / sum);
          return;
        }
        for (int c = 0; c < 4; ++c)
          self(self, static_cast<uint32_t>(t.children[c]), down.restrictTo(t.vertexCount == 4, c));
      };
      ReceiverPolynomial<Bands> down;
      down.c[0] = patchClusterIrradiance_[p];
      walk(walk, static_cast<uint32_t>(mesh_.patches[p].treeRoot), down);
    });
  });
  reflected_ = reflected;
  sourceShape_ = shapes;
  pullClusters();
}

void ReflectedLightHierarchy::gatherTreeNode(uint32_t n) {
  ReceiverPolynomial<Bands> g;
  for (uint32_t l : links_[n]) {
    if (isCluster(l)) {
      const ClusterLinkRecord &link = clusterRecords_[clusterIndex(l)];
      const Bands i = link.nearField ? meanReflected(link.source) : intensity(link.source, link.directionVector());
      for (int k = 0; k < 4; ++k) g.c[k] += i * double(link.kernel.c[k]);
      continue;
    }
    const LinkRecord &link = records_[l];
    const ReceiverPolynomial<Bands> &r = sourceShape_[link.source];
    const Bands source = r.c[0] + r.c[1] * double(link.moments[0]) + r.c[2] * double(link.moments[1]);
    for (int k = 0; k < 4; ++k) g.c[k] += source * double(link.shape.c[k]);
  }
  gathered_[n] = g;
}

int ReflectedLightHierarchy::solve(double tolerance, int maxSweeps, double &residual,
                                   const SolverProgressCallback &progress, int &total,
                                   std::chrono::steady_clock::time_point start) {
  int sweeps = 0;
  std::vector<double> change(mesh_.patches.size()), largest(mesh_.patches.size());
  while (sweeps < maxSweeps) {
    keepForTransmission();
    gatherAll();
    arena_.execute([&] {
      tbb::parallel_for(size_t(0), mesh_.patches.size(), [&](size_t p) {
        change[p] = largest[p] = 0;
        ReceiverPolynomial<Bands> down;
        down.c[0] = patchClusterIrradiance_[p];
        pushPull(static_cast<uint32_t>(mesh_.patches[p].treeRoot), down, change[p], largest[p]);
        pullShapes(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
      });
    });
    pullClusters();
    ++sweeps;
    ++total;
    double c = *std::max_element(change.begin(), change.end()), m = *std::max_element(largest.begin(), largest.end());
    residual = m > 0 ? c / m : 0;
    if (progress)
      progress({total, residual, tolerance,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
    if (residual < tolerance) break;
  }
  keepForTransmission();  // what writeTo passes through: the last sweep's
  return sweeps;
}

size_t ReflectedLightHierarchy::linkCount() const {
  size_t n = 0;
  for (const LinkRecord &l : records_) n += l.alive;
  return n + clusterLinkCount();
}

size_t ReflectedLightHierarchy::clusterLinkCount() const {
  size_t n = 0;
  for (const ClusterLinkRecord &l : clusterRecords_) n += l.alive;
  return n;
}

ReceiverPolynomial<Bands> ReflectedLightHierarchy::directShape(uint32_t n) const {
  // Through the leaf's corners' exact values, shifted so its mean is the Simpson mean (direct_).
  const MeshTreeNode &t = mesh_.tree[n];
  const bool quad = t.vertexCount == 4;
  ReceiverPolynomial<Bands> p;
  const Bands &h0 = field_.at(t.patch, t.corners[0]), &h1 = field_.at(t.patch, t.corners[1]),
              &h2 = field_.at(t.patch, t.corners[2]);
  if (quad) {
    const Bands &h3 = field_.at(t.patch, t.corners[3]);
    p.c = {h0, h1 - h0, h3 - h0, h2 - h1 - h3 + h0};
  } else {
    p.c = {h0, h1 - h0, h2 - h0, Bands(0.0)};
  }
  p.c[0] += direct_[n] - p.mean(quad);
  return p;
}

void ReflectedLightHierarchy::pullShapes(uint32_t n) {
  // R over every node as a polynomial: at a leaf ρ(H_direct + H_reflected)
  // from its own shapes, above from the children's means (fitChildMeans).
  const MeshTreeNode &t = mesh_.tree[n];
  const bool quad = t.vertexCount == 4;
  if (t.isLeaf()) {
    ReceiverPolynomial<Bands> r = directShape_[n];
    r += irradiance_[n];
    for (auto &c : r.c) c = reflectance_[n] * c;
    // What comes through from the other side, as a constant over the leaf.
    if (anyTranslucent_) {
      const auto [throughDirect, throughReflected] = transmitted(n);
      r.c[0] += throughDirect + throughReflected;
    }
    sourceShape_[n] = r;
    return;
  }
  std::array<Bands, 4> means;
  for (int c = 0; c < 4; ++c) {
    pullShapes(static_cast<uint32_t>(t.children[c]));
    means[c] = reflected_[t.children[c]];
  }
  sourceShape_[n] = fitChildMeans(quad, means);
}

void ReflectedLightHierarchy::pullDirect(uint32_t n) {
  const MeshTreeNode &t = mesh_.tree[n];
  if (t.isLeaf()) {
    direct_[n] = field_.nodeAverage(t);
    directShape_[n] = directShape(n);
    reflected_[n] = reflectance_[n] * direct_[n];
    if (anyTranslucent_) reflected_[n] += transmitted(n).first;
    return;
  }
  Bands d(0.0), r(0.0);
  for (int c = 0; c < 4; ++c) {
    const uint32_t child = static_cast<uint32_t>(t.children[c]);
    pullDirect(child);
    const double w = mesh_.tree[child].area / t.area;
    d += direct_[child] * w;
    r += reflected_[child] * w;
  }
  direct_[n] = d;
  reflected_[n] = r;
}

bool ReflectedLightHierarchy::facing(uint32_t a, uint32_t b) const {
  // Some part of b lies in front of a's plane and some part of a in front of b's.
  auto anyInFront = [&](uint32_t of, uint32_t plane) {
    const MeshTreeNode &o = mesh_.tree[of], &p = mesh_.tree[plane];
    const Vec3 n = normalOf(plane);
    const double tolerance = 1e-9 * std::sqrt(p.area);
    for (int k = 0; k < o.vertexCount; ++k)
      if (dot(o.corners[k] - p.corners[0], n) > tolerance) return true;
    return false;
  };
  return anyInFront(b, a) && anyInFront(a, b);
}

Bands ReflectedLightHierarchy::computeVariation(uint32_t n) const {
  // What a node's polynomial misses of its children: the largest difference
  // at their corners between each child's own polynomial and the node's
  // restricted to it (0 at a leaf, which has no finer information).
  const MeshTreeNode &t = mesh_.tree[n];
  Bands v(0.0);
  if (t.isLeaf()) return v;
  const bool quad = t.vertexCount == 4;
  static constexpr double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  static constexpr double triangleCorner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  for (int c = 0; c < 4; ++c) {
    const ReceiverPolynomial<Bands> parent = sourceShape_[n].restrictTo(quad, c);
    const ReceiverPolynomial<Bands> &child = sourceShape_[t.children[c]];
    for (int k = 0; k < t.vertexCount; ++k) {
      const double u = quad ? corner[k][0] : triangleCorner[k][0], w = quad ? corner[k][1] : triangleCorner[k][1];
      const Bands d = child.value(u, w) - parent.value(u, w);
      for (int b = 0; b < kBandCount; ++b) v[b] = std::max(v[b], std::abs(d[b]));
    }
  }
  return v;
}

Bands ReflectedLightHierarchy::pushPull(uint32_t n, const ReceiverPolynomial<Bands> &down, double &change,
                                        double &largest) {
  // `down`: what the ancestors (and the clusters above) gathered, in this node's parameters.
  const MeshTreeNode &t = mesh_.tree[n];
  const bool quad = t.vertexCount == 4;
  ReceiverPolynomial<Bands> h = down;
  h += gathered_[n];
  Bands r;
  if (t.isLeaf()) {
    if (n < closure_.size() && closure_[n] < 1)
      for (auto &c : h.c) c *= double(closure_[n]);
    irradiance_[n] = h;
    meanIrradiance_[n] = nonNegative(h.mean(quad));
    r = reflectance_[n] * (direct_[n] + meanIrradiance_[n]);
    if (anyTranslucent_) {
      const auto [throughDirect, throughReflected] = transmitted(n);
      r += throughDirect + throughReflected;
    }
    change = std::max({change, (r - reflected_[n]).max(), (reflected_[n] - r).max()});
    largest = std::max(largest, r.max());
  } else {
    r = Bands(0.0);
    Bands mean(0.0);
    for (int c = 0; c < 4; ++c) {
      const uint32_t child = static_cast<uint32_t>(t.children[c]);
      const double w = mesh_.tree[child].area / t.area;
      r += pushPull(child, h.restrictTo(quad, c), change, largest) * w;
      mean += meanIrradiance_[child] * w;
    }
    meanIrradiance_[n] = mean;
  }
  reflected_[n] = r;
  return r;
}

void ReflectedLightHierarchy::writeTo(Solution &s) const {
  rebuildElementsFromTrees(mesh_);
  const size_t elements = mesh_.elements.size();
  for (auto *v :
       {&s.reflectance, &s.emission, &s.radiosity, &s.direct, &s.indirect, &s.irradiance, &s.unshot, &s.transmittance})
    v->assign(elements, Bands(0.0));
  s.transmittedDirect.clear(), s.transmittedIndirect.clear();
  if (anyTranslucent_)
    s.transmittedDirect.assign(elements, Bands(0.0)), s.transmittedIndirect.assign(elements, Bands(0.0));
  s.treeRadiosity.assign(mesh_.tree.size(), Bands(0.0));
  for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
    s.treeRadiosity[n] = emission_[n] + reflected_[n];
    const int32_t e = mesh_.tree[n].element;
    if (e < 0) continue;
    s.reflectance[e] = reflectance_[n];
    s.emission[e] = emission_[n];
    const Bands reflectedIrradiance = nonNegative(irradiance_[n].mean(mesh_.tree[n].vertexCount == 4));
    s.direct[e] = reflectance_[n] * direct_[n];
    s.indirect[e] = reflectance_[n] * reflectedIrradiance;
    s.transmittance[e] = transmittance_[n];
    if (anyTranslucent_) {
      std::tie(s.transmittedDirect[e], s.transmittedIndirect[e]) = transmitted(n);
      s.direct[e] += s.transmittedDirect[e];
      s.indirect[e] += s.transmittedIndirect[e];
    }
    s.radiosity[e] = s.emission[e] + s.direct[e] + s.indirect[e];
    s.irradiance[e] = direct_[n] + reflectedIrradiance;
  }
  // At the nodes: the direct light exact, the reflected light from each
  // leaf's polynomial at its corners, averaged over the leaves around.
  s.nodeDirectIrradiance.resize(mesh_.nodes.size());
  for (uint32_t v = 0; v < mesh_.nodes.size(); ++v)
    s.nodeDirectIrradiance[v] = field_.at(mesh_.nodePatch[v], mesh_.nodes[v]);
  s.nodeIndirectIrradiance.assign(mesh_.nodes.size(), Bands(0.0));
  std::vector<double> weight(mesh_.nodes.size(), 0.0);
  static constexpr double quadCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  static constexpr double triangleCorner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
    const int32_t e = mesh_.tree[n].element;
    if (e < 0) continue;
    const Element &element = mesh_.elements[e];
    const bool quad = element.vertexCount == 4;
    for (int k = 0; k < element.vertexCount; ++k) {
      const double u = quad ? quadCorner[k][0] : triangleCorner[k][0],
                   v = quad ? quadCorner[k][1] : triangleCorner[k][1];
      s.nodeIndirectIrradiance[element.nodes[k]] += irradiance_[n].value(u, v) * element.area;
      weight[element.nodes[k]] += element.area;
    }
  }
  for (uint32_t v = 0; v < mesh_.nodes.size(); ++v) {
    if (weight[v] > 0) s.nodeIndirectIrradiance[v] = s.nodeIndirectIrradiance[v] / weight[v];
    // A polynomial extrapolated to a corner may undershoot a little where the light falls off.
    for (int b = 0; b < kBandCount; ++b) s.nodeIndirectIrradiance[v][b] = std::max(0.0, s.nodeIndirectIrradiance[v][b]);
  }
  s.links.clear();
  s.ambient = s.indirectAmbient = Bands(0.0);
  s.stats.absorbedPower = Bands(0.0);
  for (size_t e = 0; e < elements; ++e)
    s.stats.absorbedPower += s.absorptance(e) * s.irradiance[e] * mesh_.elements[e].area;
  s.stats.escapedPower = s.stats.emittedPower - s.stats.absorbedPower;
}

}  // namespace radiant
