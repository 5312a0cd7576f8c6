// `hierarchical` — hierarchical radiosity (Hanrahan, Salzman & Aupperle,
// SIGGRAPH 1991), with BF refinement and multigridding.
//
// Every input patch is the root of a quadtree (quads split at their bilinear
// midpoints, triangles into four). Energy moves along links between nodes at
// any level: Refine(p, q) links receiver p to source q when the radiosity the
// link would carry, F_pq·B_q, is below ε = linkThreshold · max E; otherwise it
// subdivides whichever of the two looks larger from the other (F_pq against
// F_qp) and recurses, down to the minimum area. Each link's form factor is the
// point-to-polygon form factor (Lambert's contour integral) at a grid of
// receiver points, each times the visibility of a stratified source point,
// averaged; the fraction of those shadow rays that arrive classifies the link
// as none, partial or full visibility.
//
// Solve: Gather (each node: H_g = Σ_links F·B_source) then Push–Pull (push
// irradiance down to the leaves, B_leaf = E + ρ·H, pull area-weighted
// averages up), repeated until B changes by less than the tolerance. A leaf
// of a translucent face adds τ·H' (transmission.h), H' the irradiance of the
// node over the same region of the other side's tree, as last pulled.
// Multigridding: the first round refines against B = E (only emitters have
// radiosity, so only their links refine), then every link is re-examined with
// the solved B and refined where it now carries too much, and the system is
// solved again (`refinementRounds` times in all).
//
// With --importance (Smits, Arvo & Salesin 1992; importance.h) the oracle
// weighs B_q by the importance of the receiver for one view, which is
// propagated over the links after each round's solve, so links that matter
// for the view are refined and the rest left coarse.
//
// Refinement only decides which links exist (from the cheap centre-to-polygon
// estimates); each link's form factor, the solver's cost, is measured after
// the refinement pass that made it, all at once: in parallel, with each MPI
// rank measuring the links into the receivers it owns (receiver id mod N,
// Hanrahan et al.'s gather is per receiver) and the ranks sharing them. A
// link's shadow rays come from its own generator, so the solution is the
// same bit for bit whatever the thread and rank counts.
//
// The leaves become the solution's elements; their corners become nodes
// shared within a patch, and T-vertices (a node in the middle of a coarser
// neighbour's edge) are recorded so interpolation stays continuous.
#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>

#include "cluster/cluster.h"
#include "radiosity/backprojection.h"
#include "radiosity/form_factor.h"
#include "radiosity/hierarchical_link.h"
#include "radiosity/importance.h"
#include "radiosity/solver.h"
#include "radiosity/transmission.h"
#include "raytrace/surface_detail.h"
#include "util/error.h"
#include "util/sampling.h"

namespace radiant {

namespace {

struct Node {
  uint32_t patch = 0;
  int vertexCount = 4;
  std::array<Vec3, 4> corners{};
  Vec3 centre, normal;
  double area = 0;
  int level = 0;
  std::array<int32_t, 4> children{-1, -1, -1, -1};
  Bands emission, reflectance, transmittance;
  Bands radiosity;                     ///< B: at a leaf E + ρH + τH', above the area average of the children
  Bands gathered, gatheredDirect;      ///< Σ F·B_source and Σ F·E_source over this node's links
  Bands irradiance, irradianceDirect;  ///< leaves: everything pushed down to them; above: their area average
  Bands lightIrradiance;               ///< from the point lights, averaged over the node (backprojection.h)
  std::vector<uint32_t> links;         ///< incoming links (indices into Hierarchy::links_)
  bool isLeaf() const { return children[0] < 0; }
};

struct HierarchicalLink {
  uint32_t receiver, source;
  double formFactor = 0, visibleFraction = 1;
  double unoccludedFormFactor = 0;  ///< F as if nothing were in between
  bool alive = true;
};

class Hierarchy {
 public:
  Hierarchy(const RayTracer &tracer, const Solution &initial, const SolverOptions &options)
      : tracer_(tracer), options_(options), arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {
    if (!tracer.scene().lights.empty()) lights_.emplace(tracer.scene(), tracer, SIZE_MAX);
    double maxEmission = 0, largestElement = 0;
    for (const Element &e : initial.mesh.elements) largestElement = std::max(largestElement, e.area);
    for (uint32_t p = 0; p < initial.mesh.patches.size(); ++p) {
      const Patch &patch = initial.mesh.patches[p];
      Node n;
      n.patch = p;
      n.vertexCount = patch.vertexCount;
      n.corners = patch.corners;
      n.normal = patch.normal;
      n.area = patch.area;
      n.centre = centreOf(n);
      // A patch's elements share its material: take ρ and E from its first element.
      n.emission = initial.emission[patch.firstElement];
      n.reflectance = initial.reflectance[patch.firstElement];
      n.transmittance = initial.transmittanceOf(patch.firstElement);
      oppositePatch_.push_back(n.transmittance.max() > 0 ? oppositePatch(tracer.scene(), initial.mesh, p) : -1);
      patchFace_.push_back(patch.face);
      // Decided by the material, not by the first element's ρ̄, which a black
      // corner of the texture makes 0 (review): diffuse, textured, not black.
      const Material &material = tracer.scene().materials[patch.material];
      textured_.push_back(material.diffuseTextureIndex >= 0 && material.diffuse.max() > 0 &&
                          (material.kind == MaterialKind::Lambertian || material.kind == MaterialKind::Glossy));
      if (textured_.back()) n.reflectance = nodeReflectance(n);
      n.lightIrradiance = lightIrradianceOf(n);
      n.radiosity = n.emission;
      // The brightest source: an emitter, or a patch the point lights make bright.
      maxEmission = std::max({maxEmission, n.emission.max(), (n.reflectance * n.lightIrradiance).max()});
      nodes_.push_back(n);
    }
    patchCount_ = static_cast<uint32_t>(nodes_.size());
    leaves_ = patchCount_;
    threshold_ = options.linkThreshold * maxEmission;
    minimumArea_ = options.minimumArea > 0 ? options.minimumArea : largestElement;
    if (options.importance)
      importance_ = std::make_unique<ImportanceRefinement>(tracer, initial.mesh, options.importanceView);
  }

  /// Links every pair of patches that can see each other, refining as needed.
  void linkPatches() {
    const uint32_t patches = static_cast<uint32_t>(nodes_.size());
    for (uint32_t p = 0; p < patches; ++p)
      for (uint32_t q = 0; q < patches; ++q)
        if (p != q && facing(nodes_[p], nodes_[q])) refine(p, q);
    measureLinks(0);
  }

  /// Multigridding: re-examines every link with the current radiosities.
  /// Returns how many links were refined.
  size_t rerefine() {
    size_t refined = 0;
    const size_t count = links_.size();
    for (size_t l = 0; l < count; ++l) {
      HierarchicalLink link = links_[l];
      if (!link.alive) continue;
      // A partly occluded link is judged by what it could carry unoccluded:
      // its visibility was sampled by area, while the form factor weights the
      // near parts of the source most, so a coarse partial link is the least
      // trustworthy kind (HSA refine them further for the same reason).
      bool partial = link.visibleFraction > 0 && link.visibleFraction < 1;
      double factor = partial ? link.unoccludedFormFactor : link.formFactor;
      if (factor * weightedSource(link.receiver, link.source) <= threshold_) continue;
      if (!canSubdivide(link.receiver) && !canSubdivide(link.source)) continue;
      links_[l].alive = false;
      auto &incoming = nodes_[link.receiver].links;
      incoming.erase(std::find(incoming.begin(), incoming.end(), uint32_t(l)));
      refineChildren(link.receiver, link.source);
      ++refined;
    }
    measureLinks(count);
    return refined;
  }

  /// Gather + push–pull until B settles; returns the sweeps taken.
  int solve(double tolerance, int maxSweeps, int &totalSweeps, double &residual, const SolverProgressCallback &progress,
            std::chrono::steady_clock::time_point start) {
    int sweeps = 0;
    for (; sweeps < maxSweeps; ++sweeps) {
      for (Node &n : nodes_) {
        n.gathered = n.gatheredDirect = Bands(0.0);
        for (uint32_t l : n.links) {
          const HierarchicalLink &link = links_[l];
          n.gathered += nodes_[link.source].radiosity * link.formFactor;
          n.gatheredDirect += nodes_[link.source].emission * link.formFactor;
        }
      }
      double change = 0, largest = 0;
      for (uint32_t root = 0; root < patchCount(); ++root) pushPull(root, Bands(0.0), Bands(0.0), change, largest);
      residual = largest > 0 ? change / largest : 0;
      ++totalSweeps;
      if (progress)
        progress({totalSweeps, residual, tolerance,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
      if (residual < tolerance) {
        ++sweeps;
        break;
      }
    }
    return sweeps;
  }

  /// --importance: propagates the view's importance over the current links
  /// (importance.h), so the next round's oracle sees it. Returns the sweeps.
  int propagateImportance(double tolerance, int maxSweeps) {
    if (!importance_) return 0;
    ImportanceGraph graph;
    graph.roots = patchCount();
    for (const Node &n : nodes_) {
      graph.children.push_back(n.children);
      graph.area.push_back(n.area);
      graph.reflectance.push_back(n.reflectance);
    }
    for (const HierarchicalLink &l : links_)
      if (l.alive) graph.links.push_back({l.receiver, l.source, l.formFactor});
    return importance_->propagate(std::move(graph), tolerance, maxSweeps);
  }

  void writeTo(Solution &s) const;
  size_t shadowRays() const { return shadowRays_; }

 private:
  /// The roots (one per patch) are the first nodes.
  uint32_t patchCount() const { return patchCount_; }

  static Vec3 centreOf(const Node &n) {
    Vec3 c;
    for (int k = 0; k < n.vertexCount; ++k) c += n.corners[k];
    return c / n.vertexCount;
  }
  std::span<const Vec3> polygon(const Node &n) const { return {n.corners.data(), size_t(n.vertexCount)}; }

  /// Some part of q lies in front of p's plane and some part of p in front of q's.
  static bool facing(const Node &p, const Node &q) {
    auto anyInFront = [](const Node &of, const Node &plane) {
      double size = std::sqrt(plane.area);
      for (int k = 0; k < of.vertexCount; ++k)
        if (dot(of.corners[k] - plane.centre, plane.normal) > 1e-9 * size) return true;
      return false;
    };
    return anyInFront(q, p) && anyInFront(p, q);
  }

  /// Cheap estimate of F(p ← q): the point-to-polygon factor at p's centre,
  /// zero when p's centre is behind q (q's front does not face it).
  double estimate(const Node &p, const Node &q) const {
    if (dot(p.centre - q.centre, q.normal) <= 0) return 0;
    return formFactorPointToPolygon(p.centre, p.normal, polygon(q));
  }

  /// Splitting stops once children would be under half the uniform mesh's
  /// element area, so the finest leaves are about --mesh-size across.
  bool canSubdivide(uint32_t n) const {
    return nodes_[n].area > 2 * minimumArea_ && leaves_ + 3 <= options_.maxElements;
  }

  /// B_q as the oracle weighs it for receiver p: its largest band, or with
  /// --importance the largest band of B_q times p's importance, relative.
  double weightedSource(uint32_t p, uint32_t q) const {
    return importance_ ? importance_->weightedRadiosity(p, nodes_[q].radiosity) : nodes_[q].radiosity.max();
  }

  void refine(uint32_t p, uint32_t q) {
    double fpq = estimate(nodes_[p], nodes_[q]), fqp = estimate(nodes_[q], nodes_[p]);
    double carried = std::max(fpq, 0.0) * weightedSource(p, q);
    // Neither centre sees the other's front, but the nodes still face each
    // other (perpendicular neighbours): the estimate is unreliable, so refine.
    bool unreliable = fpq <= 0 && fqp <= 0;
    if (!unreliable && carried <= threshold_) return link(p, q);
    if (unreliable && weightedSource(p, q) <= 0) return link(p, q);
    refineChildren(p, q, fpq, fqp);
  }

  void refineChildren(uint32_t p, uint32_t q) {
    refineChildren(p, q, estimate(nodes_[p], nodes_[q]), estimate(nodes_[q], nodes_[p]));
  }

  void refineChildren(uint32_t p, uint32_t q, double fpq, double fqp) {
    bool splitSource = canSubdivide(q) && (fpq >= fqp || !canSubdivide(p));
    if (splitSource) {
      subdivide(q);
      for (int c = 0; c < 4; ++c) {
        uint32_t child = static_cast<uint32_t>(nodes_[q].children[c]);
        if (facing(nodes_[p], nodes_[child])) refine(p, child);
      }
    } else if (canSubdivide(p)) {
      subdivide(p);
      for (int c = 0; c < 4; ++c) {
        uint32_t child = static_cast<uint32_t>(nodes_[p].children[c]);
        if (facing(nodes_[child], nodes_[q])) refine(child, q);
      }
    } else {
      link(p, q);
    }
  }

  void subdivide(uint32_t n) {
    if (!nodes_[n].isLeaf()) return;
    leaves_ += 3;
    Node parent = nodes_[n];
    MeshTreeNode shape;
    shape.vertexCount = parent.vertexCount;
    shape.corners = parent.corners;
    const auto children = childCorners(shape);  // the layout the mesh's point location descends
    for (int k = 0; k < 4; ++k) {
      Node child;
      child.patch = parent.patch;
      child.vertexCount = parent.vertexCount;
      child.corners = children[k];
      child.normal = parent.normal;
      child.area = 0;
      for (int v = 1; v + 1 < child.vertexCount; ++v)
        child.area += 0.5 * length(cross(child.corners[v] - child.corners[0], child.corners[v + 1] - child.corners[0]));
      child.centre = centreOf(child);
      child.level = parent.level + 1;
      child.emission = parent.emission;
      child.reflectance = textured_[parent.patch] ? nodeReflectance(child) : parent.reflectance;
      child.transmittance = parent.transmittance;
      child.radiosity = parent.radiosity;
      child.lightIrradiance = lightIrradianceOf(child);
      nodes_[n].children[k] = static_cast<int32_t>(nodes_.size());
      nodes_.push_back(child);
    }
    if (importance_) {
      std::array<uint32_t, 4> ids;
      std::array<ImportanceNodeShape, 4> shapes;
      for (int k = 0; k < 4; ++k) {
        ids[k] = static_cast<uint32_t>(nodes_[n].children[k]);
        shapes[k] = {nodes_[ids[k]].vertexCount, nodes_[ids[k]].corners, nodes_[ids[k]].area};
      }
      importance_->split(n, ids, shapes, parent.normal);
    }
  }

  /// Link p ← q's form factor (hierarchical_link.h).
  LinkMeasure measure(uint32_t p, uint32_t q) const {
    auto end = [&](const Node &n) { return HierarchicalLinkEnd{n.vertexCount, n.corners, n.centre, n.normal, n.area}; };
    return measureHierarchicalLink(tracer_, end(nodes_[p]), end(nodes_[q]), options_.visibilitySamples,
                                   sampleGenerator(options_.seed, (uint64_t(p) << 32) | q, 0x4852));
  }

  /// Links receiver p to source q; measureLinks() gives it its form factor.
  void link(uint32_t p, uint32_t q) {
    nodes_[p].links.push_back(static_cast<uint32_t>(links_.size()));
    links_.push_back({p, q});
  }

  /// Rank r measures the links into the receivers r, r + N, r + 2N, …
  static bool ownsReceiver(uint32_t node) {
    return cluster::size() == 1 || node % uint32_t(cluster::size()) == uint32_t(cluster::rank());
  }

  /// Measures links `from`… (those the last refinement made), in parallel and
  /// split over the ranks by receiver, then shares them (class comment).
  void measureLinks(size_t from) {
    // In batches, so the measures held at once (and each sum between the ranks) stay bounded.
    constexpr size_t kBatch = size_t(1) << 16;
    std::vector<LinkMeasure> measures;
    std::vector<size_t> all;
    for (size_t first = from; first < links_.size(); first += kBatch) {
      const size_t count = std::min(kBatch, links_.size() - first);
      measures.assign(count, LinkMeasure{});
      auto owns = [&](size_t i) { return ownsReceiver(links_[first + i].receiver); };
      arena_.execute([&] {
        tbb::parallel_for(size_t(0), count, [&](size_t i) {
          if (owns(i)) measures[i] = measure(links_[first + i].receiver, links_[first + i].source);
        });
      });
      all.resize(count);
      for (size_t i = 0; i < count; ++i) all[i] = i;
      cluster::shareOwnedEntries(measures, all, owns);
      for (size_t i = 0; i < count; ++i) {
        HierarchicalLink &l = links_[first + i];
        l.formFactor = measures[i].formFactor;
        l.visibleFraction = measures[i].visibleFraction();
        l.unoccludedFormFactor = measures[i].unoccludedFormFactor;
        shadowRays_ += measures[i].shadowRays;
      }
    }
  }

  Bands pushPull(uint32_t n, const Bands &down, const Bands &downDirect, double &change, double &largest) {
    Node &node = nodes_[n];
    Bands h = down + node.gathered, hd = downDirect + node.gatheredDirect;
    Bands b;
    if (node.isLeaf()) {
      // The point lights' light, shot before anything else, is direct light too.
      h += node.lightIrradiance;
      hd += node.lightIrradiance;
      node.irradiance = h;
      node.irradianceDirect = hd;
      b = node.emission + node.reflectance * h + node.transmittance * transmitted(node).first;
      change = std::max(change, (b - node.radiosity).max());
      change = std::max(change, (node.radiosity - b).max());
      largest = std::max(largest, (b - node.emission).max());  // reflected radiosity: emitters would mask the walls
    } else {
      b = Bands(0.0);
      Bands irradiance(0.0), irradianceDirect(0.0);
      for (int c = 0; c < 4; ++c) {
        uint32_t child = static_cast<uint32_t>(node.children[c]);
        const double w = nodes_[child].area / nodes_[n].area;
        b += pushPull(child, h, hd, change, largest) * w;
        irradiance += nodes_[child].irradiance * w;
        irradianceDirect += nodes_[child].irradianceDirect * w;
      }
      nodes_[n].irradiance = irradiance;
      nodes_[n].irradianceDirect = irradianceDirect;
    }
    nodes_[n].radiosity = b;
    return b;
  }

  /// H' and its direct part: the irradiance of the other side of a
  /// translucent leaf's face over the same region; 0 for an opaque one.
  std::pair<Bands, Bands> transmitted(const Node &leaf) const {
    const int32_t other = oppositePatch_[leaf.patch];
    if (other < 0) return {Bands(0.0), Bands(0.0)};
    const Node &m = nodes_[coveringNode(nodes_, uint32_t(other), leaf.centre, nodes_[size_t(other)].normal, leaf.area)];
    return {m.irradiance, m.irradianceDirect};
  }

  /// What the point lights give the node, averaged over it; 0 without lights.
  Bands lightIrradianceOf(const Node &n) const {
    if (!lights_) return Bands(0.0);
    return meanPointLightIrradiance(*lights_, tracer_.scene(), std::span<const Vec3>(n.corners.data(), n.vertexCount),
                                    n.normal);
  }

  /// ρ̄ of a textured patch's node: the texture averaged over the node (C&W eq. 9.11).
  Bands nodeReflectance(const Node &n) const {
    return averageDiffuse(tracer_.scene(), patchFace_[n.patch], std::span<const Vec3>(n.corners.data(), n.vertexCount));
  }

  const RayTracer &tracer_;
  std::vector<uint32_t> patchFace_;     ///< the scene face of each patch
  std::vector<bool> textured_;          ///< per patch: its ρ varies with a texture
  std::vector<int32_t> oppositePatch_;  ///< per patch of a translucent face: the other side's, else −1
  const SolverOptions &options_;
  std::vector<Node> nodes_;
  std::vector<HierarchicalLink> links_;
  double threshold_ = 0, minimumArea_ = 0;
  size_t shadowRays_ = 0;
  uint32_t patchCount_ = 0;
  size_t leaves_ = 0;                                 ///< current leaf count, bounded by options.maxElements
  std::unique_ptr<ImportanceRefinement> importance_;  ///< --importance only
  std::optional<DirectIrradiance> lights_;            ///< scenes with point lights only
  tbb::task_arena arena_;                             ///< --threads for measuring links
};

void Hierarchy::writeTo(Solution &s) const {
  RadiosityMesh mesh;
  mesh.patchOfFace = s.mesh.patchOfFace;
  mesh.patches = s.mesh.patches;
  mesh.patchCornerNormals = s.mesh.patchCornerNormals;
  mesh.tree.resize(nodes_.size());
  for (uint32_t n = 0; n < nodes_.size(); ++n) {
    const Node &node = nodes_[n];
    MeshTreeNode &t = mesh.tree[n];
    t.children = node.children;
    t.patch = node.patch;
    t.vertexCount = node.vertexCount;
    t.corners = node.corners;
    t.area = node.area;
  }
  for (uint32_t p = 0; p < patchCount(); ++p) {
    mesh.patches[p].treeRoot = static_cast<int32_t>(p);
    mesh.patches[p].divisionsU = mesh.patches[p].divisionsV = 1;
  }
  rebuildElementsFromTrees(mesh);

  const size_t elements = mesh.elements.size();
  for (auto *v :
       {&s.reflectance, &s.emission, &s.radiosity, &s.direct, &s.indirect, &s.irradiance, &s.unshot, &s.transmittance})
    v->assign(elements, Bands(0.0));
  for (uint32_t n = 0; n < nodes_.size(); ++n) {
    if (mesh.tree[n].element < 0) continue;
    const Node &node = nodes_[n];
    const size_t e = static_cast<size_t>(mesh.tree[n].element);
    s.reflectance[e] = node.reflectance;
    s.transmittance[e] = node.transmittance;
    s.emission[e] = node.emission;
    s.radiosity[e] = node.radiosity;
    s.irradiance[e] = node.irradiance;
    s.direct[e] = node.reflectance * node.irradianceDirect + node.transmittance * transmitted(node).second;
    s.indirect[e] = node.radiosity - node.emission - s.direct[e];
  }
  s.treeRadiosity.resize(nodes_.size());
  for (uint32_t n = 0; n < nodes_.size(); ++n) s.treeRadiosity[n] = nodes_[n].radiosity;
  s.links.clear();
  for (const HierarchicalLink &l : links_) {
    if (!l.alive) continue;
    Link out;
    out.receiver = l.receiver;
    out.source = l.source;
    out.formFactor = static_cast<float>(l.formFactor);
    out.visibleFraction = static_cast<float>(l.visibleFraction);
    out.visibility = l.visibleFraction <= 0   ? LinkVisibility::None
                     : l.visibleFraction >= 1 ? LinkVisibility::Full
                                              : LinkVisibility::Partial;
    const Node &r = nodes_[l.receiver];
    out.carriedPower =
        static_cast<float>((r.reflectance * nodes_[l.source].radiosity).average() * l.formFactor * r.area);
    s.links.push_back(out);
  }
  s.mesh = std::move(mesh);
  s.ambient = Bands(0.0);
  s.stats.absorbedPower = Bands(0.0);
  for (size_t e = 0; e < s.elementCount(); ++e)
    s.stats.absorbedPower += s.absorptance(e) * s.irradiance[e] * s.mesh.elements[e].area;
  // The escaped power is measured by solveRadiosity (power_balance.h), not inferred from this.
}

}  // namespace

void solveHierarchical(const RayTracer &tracer, Solution &s, const SolverOptions &options,
                       const SolverProgressCallback &progress) {
  const auto start = std::chrono::steady_clock::now();
  Hierarchy hierarchy(tracer, s, options);
  hierarchy.linkPatches();
  const int maxSweeps = options.maxIterations > 0 ? options.maxIterations : 1000;
  int totalSweeps = 0;
  double residual = 0;
  const int rounds = std::max(1, options.refinementRounds);
  for (int round = 0; round < rounds; ++round) {
    if (round > 0 && hierarchy.rerefine() == 0) break;
    hierarchy.solve(options.tolerance, maxSweeps, totalSweeps, residual, progress, start);
    // Smits et al. refine against both solutions: importance travels over
    // the links just solved, for the next round's re-examination.
    if (round + 1 < rounds) hierarchy.propagateImportance(options.tolerance, maxSweeps);
  }
  s.stats.iterations = totalSweeps;
  s.stats.residual = residual;
  hierarchy.writeTo(s);
  s.stats.formFactorRays = hierarchy.shadowRays();
}

}  // namespace radiant
