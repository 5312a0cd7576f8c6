// `hierarchical-exact` — the default solver: the direct light exact at every
// mesh node, the reflected light by hierarchical radiosity.
//
// The radiosity B = E + ρ(H_direct + H_reflected) is split where the two
// parts need different tools:
//
// 1. H_direct, the light arriving straight from the emitters, carries the
//    shadows and penumbrae. It is computed exactly, point by point, by
//    backprojection (radiosity/backprojection.h), and the patch trees are
//    refined until it interpolates bilinearly within a tolerance
//    (radiosity/direct_refinement.h). Each element's mean is Simpson's rule
//    over those exact values; the display interpolates the exact values at
//    the nodes (Solution::nodeDirectIrradiance), so shadows are as sharp as
//    the mesh, and no shadow ray's noise enters them.
// 2. H_reflected, the light reflected at least once, is smooth and is
//    carried by hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991)
//    over links between nodes of the same trees, gathering the sources'
//    reflected radiosity R = B − E. A link's form factor is exact at each of
//    the receiver's cubature points, visibility included (backprojection
//    over the faces in the link's shaft: radiosity/link_estimate.h), and is
//    kept as polynomials over the receiver, one per term of the source's R,
//    itself a polynomial (radiosity/receiver_polynomial.h): what a leaf
//    receives from a coarse link, and what a source sends from its bright and
//    dark parts, are right to second order. The refinement oracle bounds the
//    error a link makes rather than the light it carries (Bekaert & Willems
//    1996, "Error control for radiosity"; RenderPark's Galerkin radiosity):
//    how far the point form factors stray from their polynomial times the
//    source's R, plus the form factor times how far the source's children
//    stray from its polynomial. A link whose error exceeds the threshold is
//    replaced by links from the children of the larger of its two nodes.
//
// Refinement runs in batches: every pending pair's form factor in a batch is
// estimated in parallel, then the decisions are applied in order, so the
// solution does not depend on the thread count. Then gather (each node sums
// its links' polynomials, in parallel) and push–pull (per patch, in parallel)
// until R settles; then the links are re-examined with the solved R
// (multigridding) and the system solved again.
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <deque>
#include <chrono>
#include <cmath>

#include "radiosity/backprojection.h"
#include "radiosity/direct_refinement.h"
#include "radiosity/form_factor.h"
#include "radiosity/link_estimate.h"
#include "radiosity/receiver_polynomial.h"
#include "radiosity/solver.h"
#include "texture/surface_detail.h"

namespace radiant {

namespace {

double longestEdge(const MeshTreeNode &n) {
  double longest = 0;
  for (int k = 0; k < n.vertexCount; ++k)
    longest = std::max(longest, length(n.corners[(k + 1) % n.vertexCount] - n.corners[k]));
  return longest;
}

struct PendingPair {
  uint32_t receiver, source;
  bool clearShaft = false;  ///< known unoccluded from a parent pair
};

/// A link as the hierarchy keeps it: 68 bytes with its index in the
/// receiver's list (the form factor is shape[0]'s mean over the receiver).
struct LinkRecord {
  uint32_t receiver, source;
  std::array<ReceiverPolynomial<float>, 3> shape;
  float spread = 0;
  bool clearShaft = false;
  bool alive = true;
};

class ReflectedLightHierarchy {
 public:
  ReflectedLightHierarchy(const Scene &scene, const RayTracer &tracer, RadiosityMesh &mesh, DirectLightField &field,
                          const SolverOptions &options, double minimumEdge)
      : scene_(scene), tracer_(tracer), mesh_(mesh), field_(field), options_(options), faces_(scene),
        estimator_(scene, faces_), minimumEdge_(minimumEdge), arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {
    const Box3 &b = faces_.sceneBounds();
    scale_ = std::max(1e-9, length(b.hi - b.lo));
    for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
      addNodeData(n);
      leaves_ += mesh_.tree[n].isLeaf();
    }
  }

  /// The node's data arrays follow mesh.tree; called for every new tree node.
  void addNodeData(uint32_t n) {
    const MeshTreeNode &t = mesh_.tree[n];
    const Patch &patch = mesh_.patches[t.patch];
    const Material &material = scene_.materials[patch.material];
    Bands rho = material.kind == MaterialKind::Lambertian || material.kind == MaterialKind::Glossy ? material.diffuse
                                                                                                    : Bands(0.0);
    if (material.diffuseTextureIndex >= 0 && rho.max() > 0)
      rho = averageDiffuse(scene_, patch.face, std::span<const Vec3>(t.corners.data(), size_t(t.vertexCount)));
    reflectance_.push_back(rho);
    emission_.push_back(material.emission * kPi);
    reflected_.push_back(Bands(0.0));
    sourceShape_.emplace_back();
    directShape_.emplace_back();
    gathered_.emplace_back();
    irradiance_.emplace_back();
    direct_.push_back(Bands(0.0));
    links_.emplace_back();
  }

  /// The direct light's mean over every node, from the field (evaluating what
  /// is missing), and R = ρ·H_direct as the first estimate of the sources.
  void initialiseFromDirectLight() {
    std::vector<std::pair<uint32_t, Vec3>> points;
    std::vector<Vec3> nodePoints;
    for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
      if (!mesh_.tree[n].isLeaf()) continue;
      DirectLightField::testPoints(mesh_.tree[n], nodePoints);
      for (const Vec3 &p : nodePoints) points.push_back({mesh_.tree[n].patch, p});
    }
    field_.evaluate(mesh_, points, options_.threads);
    for (uint32_t p = 0; p < mesh_.patches.size(); ++p) {
      pullDirect(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
      pullShapes(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
    }
  }

  /// The link error allowed, W·m⁻² of reflected radiosity.
  void setThreshold(double absolute) { threshold_ = absolute; }

  void linkPatches() {
    std::vector<PendingPair> pending;
    for (uint32_t p = 0; p < mesh_.patches.size(); ++p)
      for (uint32_t q = 0; q < mesh_.patches.size(); ++q) {
        const uint32_t a = static_cast<uint32_t>(mesh_.patches[p].treeRoot), b = static_cast<uint32_t>(mesh_.patches[q].treeRoot);
        if (p != q && facing(a, b)) pending.push_back({a, b, false});
      }
    refine(std::move(pending));
  }

  /// Multigridding: re-examines every link with the current R; returns how many were refined.
  size_t rerefine() {
    std::vector<PendingPair> pending;
    for (size_t l = 0; l < records_.size(); ++l) {
      LinkRecord &link = records_[l];
      if (!link.alive || error(link.receiver, link.source, formFactorOf(link), link.spread) <= threshold_) continue;
      if (!canSplit(link.receiver) && !canSplit(link.source)) continue;
      link.alive = false;
      auto &incoming = links_[link.receiver];
      incoming.erase(std::find(incoming.begin(), incoming.end(), uint32_t(l)));
      split(link.receiver, link.source, link.clearShaft, pending);
    }
    const size_t refined = pending.size();
    refine(std::move(pending));
    return refined;
  }

  /// Gather + push–pull until R settles; returns the sweeps taken.
  int solve(double tolerance, int maxSweeps, double &residual, const SolverProgressCallback &progress, int &total,
            std::chrono::steady_clock::time_point start) {
    int sweeps = 0;
    const uint32_t nodes = static_cast<uint32_t>(mesh_.tree.size());
    std::vector<double> change(mesh_.patches.size()), largest(mesh_.patches.size());
    while (sweeps < maxSweeps) {
      arena_.execute([&] {
        tbb::parallel_for(uint32_t(0), nodes, [&](uint32_t n) {
          ReceiverPolynomial<Bands> g;
          for (uint32_t l : links_[n]) {
            const LinkRecord &link = records_[l];
            const ReceiverPolynomial<Bands> &r = sourceShape_[link.source];
            for (int j = 0; j < 3; ++j)
              for (int k = 0; k < 4; ++k) g.c[k] += r.c[j] * double(link.shape[j].c[k]);
          }
          gathered_[n] = g;
        });
        tbb::parallel_for(size_t(0), mesh_.patches.size(), [&](size_t p) {
          change[p] = largest[p] = 0;
          pushPull(static_cast<uint32_t>(mesh_.patches[p].treeRoot), ReceiverPolynomial<Bands>(), change[p], largest[p]);
          pullShapes(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
        });
      });
      ++sweeps;
      ++total;
      double c = *std::max_element(change.begin(), change.end()), m = *std::max_element(largest.begin(), largest.end());
      residual = m > 0 ? c / m : 0;
      if (progress)
        progress({total, residual, tolerance,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
      if (residual < tolerance) break;
    }
    return sweeps;
  }

  void writeTo(Solution &s) const;
  size_t rays() const { return rays_; }
  size_t linkCount() const {
    size_t n = 0;
    for (const LinkRecord &l : records_) n += l.alive;
    return n;
  }

 private:
  const Vec3 &normalOf(uint32_t n) const { return mesh_.patches[mesh_.tree[n].patch].normal; }
  double formFactorOf(const LinkRecord &l) const {
    return l.shape[0].mean(mesh_.tree[l.receiver].vertexCount == 4);
  }
  LinkEnd end(uint32_t n) const { return {mesh_.tree[n], normalOf(n), mesh_.patches[mesh_.tree[n].patch].face}; }

  /// The direct light over a leaf as a polynomial: through its corners'
  /// exact values, shifted so its mean is the Simpson mean (direct_).
  ReceiverPolynomial<Bands> directShape(uint32_t n) const {
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

  /// R over every node as a polynomial: at a leaf ρ(H_direct + H_reflected)
  /// from its own shapes, above from the children's means (fitChildMeans).
  void pullShapes(uint32_t n) {
    const MeshTreeNode &t = mesh_.tree[n];
    const bool quad = t.vertexCount == 4;
    if (t.isLeaf()) {
      ReceiverPolynomial<Bands> r = directShape_[n];
      r += irradiance_[n];
      for (auto &c : r.c) c = reflectance_[n] * c;
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

  void pullDirect(uint32_t n) {
    const MeshTreeNode &t = mesh_.tree[n];
    if (t.isLeaf()) {
      direct_[n] = field_.nodeAverage(t);
      directShape_[n] = directShape(n);
      reflected_[n] = reflectance_[n] * direct_[n];
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

  /// Some part of b lies in front of a's plane and some part of a in front of b's.
  bool facing(uint32_t a, uint32_t b) const {
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

  bool canSplit(uint32_t n) const {
    return longestEdge(mesh_.tree[n]) >= 2 * minimumEdge_ && leafCount() + 3 <= options_.maxElements;
  }
  size_t leafCount() const { return leaves_; }

  /// What a node's polynomial misses of its children: the largest difference
  /// at their corners between each child's own polynomial and the node's
  /// restricted to it (0 at a leaf, which has no finer information).
  Bands variation(uint32_t n) const {
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

  /// The oracle: the error in the reflected radiosity of the receiver that
  /// the link would make, W·m⁻² (max band).
  double error(uint32_t r, uint32_t s, double formFactor, double spreadOfF) const {
    const Bands spread = reflected_[s] * spreadOfF + variation(s) * formFactor;
    // The irradiance of a black receiver matters too (what it absorbs, the
    // illuminance it reports): weigh it as a dark grey one, not by 0.
    constexpr double kLeastReflectance = 0.05;
    double worst = 0;
    for (int b = 0; b < kBandCount; ++b)
      worst = std::max(worst, std::max(reflectance_[r][b], kLeastReflectance) * spread[b]);
    return worst;
  }

  void splitNode(uint32_t n) {
    if (!mesh_.tree[n].isLeaf()) return;
    splitTreeNode(mesh_, n);
    leaves_ += 3;
    for (int c = 0; c < 4; ++c) {
      const uint32_t child = static_cast<uint32_t>(mesh_.tree[n].children[c]);
      addNodeData(child);
      reflected_[child] = reflected_[n];
      direct_[child] = direct_[n];
      sourceShape_[child] = sourceShape_[n].restrictTo(mesh_.tree[n].vertexCount == 4, c);
      irradiance_[child] = irradiance_[n].restrictTo(mesh_.tree[n].vertexCount == 4, c);
    }
    newLeaves_.push_back(n);
  }

  /// Replaces the pair by pairs with the children of the larger node.
  void split(uint32_t r, uint32_t s, bool clearShaft, std::vector<PendingPair> &pending) {
    // The larger of the two (RenderPark's rule; splitting by which term of
    // the error dominates made more links and a worse image).
    const bool receiverFirst = mesh_.tree[r].area >= mesh_.tree[s].area;
    const bool splitReceiver = canSplit(r) && (receiverFirst || !canSplit(s));
    const uint32_t node = splitReceiver ? r : s;
    splitNode(node);
    for (int c = 0; c < 4; ++c) {
      const uint32_t child = static_cast<uint32_t>(mesh_.tree[node].children[c]);
      const uint32_t rr = splitReceiver ? child : r, ss = splitReceiver ? s : child;
      if (facing(rr, ss)) pending.push_back({rr, ss, clearShaft});
    }
  }

  void refine(std::vector<PendingPair> pending) {
    // In batches from the back of the queue, so that the estimates held at
    // once (about 250 bytes each) stay bounded however many pairs wait.
    constexpr size_t kBatch = size_t(1) << 15;
    std::vector<LinkEstimate> estimates;
    std::vector<PendingPair> batch;
    std::vector<size_t> kept;
    while (!pending.empty()) {
      const size_t count = std::min(kBatch, pending.size());
      batch.assign(pending.end() - static_cast<std::ptrdiff_t>(count), pending.end());
      pending.resize(pending.size() - count);
      estimates.assign(count, LinkEstimate{});
      arena_.execute([&] {
        tbb::parallel_for(size_t(0), count, [&](size_t i) {
          estimates[i] = estimator_.estimate(end(batch[i].receiver), end(batch[i].source), batch[i].clearShaft);
        });
      });
      kept.clear();
      for (size_t i = 0; i < count; ++i) {
        const uint32_t r = batch[i].receiver, s = batch[i].source;
        rays_ += estimates[i].rays;
        if (error(r, s, estimates[i].formFactor, estimates[i].spread) > threshold_ && (canSplit(r) || canSplit(s))) {
          split(r, s, estimates[i].clearShaft, pending);
          continue;
        }
        if (estimates[i].formFactor > 0) kept.push_back(i);
      }
      // Only the links kept need the source's terms of their shape.
      arena_.execute([&] {
        tbb::parallel_for(size_t(0), kept.size(), [&](size_t k) {
          const size_t i = kept[k];
          estimator_.completeShape(end(batch[i].receiver), end(batch[i].source), estimates[i]);
        });
      });
      for (size_t i : kept) {
        const uint32_t r = batch[i].receiver, s = batch[i].source;
        links_[r].push_back(static_cast<uint32_t>(records_.size()));
        records_.push_back({r, s, estimates[i].shape, float(estimates[i].spread), estimates[i].clearShaft, true});
      }
    }
    // New leaves need the direct light at their test points, and their R.
    if (!newLeaves_.empty()) {
      initialiseNewLeaves();
      newLeaves_.clear();
    }
  }

  void initialiseNewLeaves() {
    std::vector<std::pair<uint32_t, Vec3>> points;
    std::vector<Vec3> nodePoints;
    for (uint32_t n : newLeaves_)
      for (int c = 0; c < 4; ++c) {
        const MeshTreeNode &child = mesh_.tree[mesh_.tree[n].children[c]];
        if (!child.isLeaf()) continue;
        DirectLightField::testPoints(child, nodePoints);
        for (const Vec3 &p : nodePoints) points.push_back({child.patch, p});
      }
    field_.evaluate(mesh_, points, options_.threads);
    for (uint32_t n : newLeaves_)
      for (int c = 0; c < 4; ++c) {
        const uint32_t child = static_cast<uint32_t>(mesh_.tree[n].children[c]);
        if (mesh_.tree[child].isLeaf()) {
          direct_[child] = field_.nodeAverage(mesh_.tree[child]);
          directShape_[child] = directShape(child);
        }
      }
  }

  /// `down`: what the ancestors gathered, in this node's parameters.
  Bands pushPull(uint32_t n, const ReceiverPolynomial<Bands> &down, double &change, double &largest) {
    const MeshTreeNode &t = mesh_.tree[n];
    const bool quad = t.vertexCount == 4;
    ReceiverPolynomial<Bands> h = down;
    h += gathered_[n];
    Bands r;
    if (t.isLeaf()) {
      irradiance_[n] = h;
      r = reflectance_[n] * (direct_[n] + h.mean(quad));
      change = std::max({change, (r - reflected_[n]).max(), (reflected_[n] - r).max()});
      largest = std::max(largest, r.max());
    } else {
      r = Bands(0.0);
      for (int c = 0; c < 4; ++c) {
        const uint32_t child = static_cast<uint32_t>(t.children[c]);
        r += pushPull(child, h.restrictTo(quad, c), change, largest) * (mesh_.tree[child].area / t.area);
      }
    }
    reflected_[n] = r;
    return r;
  }

  const Scene &scene_;
  const RayTracer &tracer_;
  RadiosityMesh &mesh_;
  DirectLightField &field_;
  const SolverOptions &options_;
  FaceTree faces_;
  LinkEstimator estimator_;
  double minimumEdge_ = 0, threshold_ = 0, scale_ = 1;
  mutable tbb::task_arena arena_;
  // Per tree node.
  std::vector<Bands> reflectance_, emission_, reflected_, direct_;
  /// R over each node as a polynomial in its parameters (mean: reflected_),
  /// and at the leaves H_direct's (directShape).
  std::vector<ReceiverPolynomial<Bands>> sourceShape_, directShape_;
  /// What each node gathered over its own links, and at the leaves all they received, as polynomials.
  std::vector<ReceiverPolynomial<Bands>> gathered_, irradiance_;
  std::vector<std::vector<uint32_t>> links_;  ///< incoming links, indices into records_
  /// A deque, not a vector: growing it never copies it, so its peak memory
  /// is what it holds (a vector's doubling held 3× its links for a moment).
  std::deque<LinkRecord> records_;
  std::vector<uint32_t> newLeaves_;  ///< split since the direct light was last read
  size_t leaves_ = 0;
  size_t rays_ = 0;

};

void ReflectedLightHierarchy::writeTo(Solution &s) const {
  rebuildElementsFromTrees(mesh_);
  const size_t elements = mesh_.elements.size();
  for (auto *v : {&s.reflectance, &s.emission, &s.radiosity, &s.direct, &s.indirect, &s.irradiance, &s.unshot})
    v->assign(elements, Bands(0.0));
  s.treeRadiosity.assign(mesh_.tree.size(), Bands(0.0));
  for (uint32_t n = 0; n < mesh_.tree.size(); ++n) {
    s.treeRadiosity[n] = emission_[n] + reflected_[n];
    const int32_t e = mesh_.tree[n].element;
    if (e < 0) continue;
    s.reflectance[e] = reflectance_[n];
    s.emission[e] = emission_[n];
    const Bands reflectedIrradiance = irradiance_[n].mean(mesh_.tree[n].vertexCount == 4);
    s.direct[e] = reflectance_[n] * direct_[n];
    s.indirect[e] = reflectance_[n] * reflectedIrradiance;
    s.radiosity[e] = s.emission[e] + s.direct[e] + s.indirect[e];
    s.irradiance[e] = direct_[n] + reflectedIrradiance;
  }
  // At the nodes: the direct light exact, the reflected light from each
  // leaf's polynomial at its corners, averaged over the leaves around.
  s.nodeDirectIrradiance.resize(mesh_.nodes.size());
  for (uint32_t v = 0; v < mesh_.nodes.size(); ++v) s.nodeDirectIrradiance[v] = field_.at(mesh_.nodePatch[v], mesh_.nodes[v]);
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
      const double u = quad ? quadCorner[k][0] : triangleCorner[k][0], v = quad ? quadCorner[k][1] : triangleCorner[k][1];
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
    s.stats.absorbedPower += (Bands(1.0) - s.reflectance[e]) * s.irradiance[e] * mesh_.elements[e].area;
  s.stats.escapedPower = s.stats.emittedPower - s.stats.absorbedPower;
}

/// The area mean of ρ·H_direct (max band) over the trees' leaves, W·m⁻².
double meanFirstBounce(const RadiosityMesh &mesh, DirectLightField &field, const std::vector<Bands> &patchReflectance,
                       int threads) {
  std::vector<std::pair<uint32_t, Vec3>> points;
  std::vector<Vec3> nodePoints;
  for (const MeshTreeNode &t : mesh.tree) {
    if (!t.isLeaf()) continue;
    DirectLightField::testPoints(t, nodePoints);
    for (const Vec3 &p : nodePoints) points.push_back({t.patch, p});
  }
  field.evaluate(mesh, points, threads);
  double sum = 0, area = 0;
  for (const MeshTreeNode &t : mesh.tree) {
    if (!t.isLeaf()) continue;
    sum += (patchReflectance[t.patch] * field.nodeAverage(t)).max() * t.area;
    area += t.area;
  }
  return area > 0 ? sum / area : 0;
}

}  // namespace

void solveHierarchicalExact(const RayTracer &tracer, Solution &s, const SolverOptions &options,
                            const SolverProgressCallback &progress) {
  const auto start = std::chrono::steady_clock::now();
  const Scene &scene = tracer.scene();
  RadiosityMesh &mesh = s.mesh;
  // A uniform mesh (a caller's, not meshAndSolve's): its patches become the
  // trees' roots, and the refinement below makes the elements again.
  if (mesh.tree.empty()) {
    makePatchTrees(mesh);
    rebuildElementsFromTrees(mesh);
  }

  // 1. The direct light, exact, and the trees refined for it.
  DirectIrradiance direct(scene);
  DirectLightField field(scene, direct);
  std::vector<Bands> patchReflectance(mesh.patches.size());
  for (uint32_t p = 0; p < mesh.patches.size(); ++p) {
    const Material &m = scene.materials[mesh.patches[p].material];
    patchReflectance[p] = m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.diffuse : Bands(0.0);
  }
  const double extent = [&] {
    Box3 b;
    for (const Vec3 &p : scene.positions) b.extend(p);
    return std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z, 1e-9});
  }();
  DirectRefinementOptions refinement;
  refinement.minimumEdge = options.directMinimumEdge > 0 ? options.directMinimumEdge : extent / 256;
  refinement.maxElements = options.maxElements;
  refinement.threads = options.threads;
  // Both tolerances are relative to the scene's mean first-bounce radiosity,
  // the area mean of ρ·H_direct, measured on the starting mesh.
  const double firstBounce = meanFirstBounce(mesh, field, patchReflectance, options.threads);
  refinement.tolerance = options.directTolerance * firstBounce;
  refineForDirectLight(mesh, patchReflectance, field, refinement);
  const bool timing = std::getenv("RADIANT_TIMING") != nullptr;
  auto lap = [&, last = start](const char *what) mutable {
    if (!timing) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "  %-28s %.3f s\n", what, std::chrono::duration<double>(now - last).count());
    last = now;
  };
  lap("direct light and its mesh");

  // 2. The reflected light by hierarchical radiosity on the same trees.
  const double minimumEdge = options.linkMinimumEdge > 0 ? options.linkMinimumEdge : extent / 64;
  ReflectedLightHierarchy hierarchy(scene, tracer, mesh, field, options, minimumEdge);
  hierarchy.initialiseFromDirectLight();
  hierarchy.setThreshold(options.linkError * firstBounce);
  hierarchy.linkPatches();
  lap("linking");
  const int maxSweeps = options.maxIterations > 0 ? options.maxIterations : 1000;
  int total = 0;
  double residual = 0;
  for (int round = 0; round < std::max(1, options.refinementRounds); ++round) {
    if (round > 0 && hierarchy.rerefine() == 0) break;
    lap("re-linking");
    hierarchy.solve(options.tolerance, maxSweeps, residual, progress, total, start);
    lap("solving");
  }
  s.stats.iterations = total;
  s.stats.residual = residual;
  s.stats.formFactorRays = hierarchy.rays();
  hierarchy.writeTo(s);
  lap("writing the solution");
  if (timing) std::fprintf(stderr, "  links %zu, sweeps %d\n", hierarchy.linkCount(), total);
}

}  // namespace radiant
