// ReflectedLightHierarchy's refinement: the first linking from the root
// cluster with itself, re-linking with the solved radiosities, and the
// oracle that decides, pair by pair, whether a link is kept or its larger
// end split (Hanrahan, Salesin & Aupperle 1991; with clusters, Smits, Arvo &
// Greenberg 1994). The tree nodes' part and the solve are in
// reflected_light_hierarchy.cpp; what the whole does is in
// reflected_light_hierarchy.h.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "cluster/cluster.h"
#include "radiosity/reflected_light_hierarchy.h"

namespace radiant {

void ReflectedLightHierarchy::link() {
  if (clusters_.clusters.empty()) return;
  updateVariation();
  refine({{clusterId(0), clusterId(0), false}});
  // The ambient estimate only guided the refinement: the solve starts from
  // the direct light alone, so that a closed room no light reaches stays
  // exactly 0 (from any positive start, the sweeps would only shrink it).
  for (uint32_t p = 0; p < mesh_.patches.size(); ++p) {
    double change = 0, largest = 0;
    pushPull(static_cast<uint32_t>(mesh_.patches[p].treeRoot), ReceiverPolynomial<Bands>(), change, largest);
    pullShapes(static_cast<uint32_t>(mesh_.patches[p].treeRoot));
  }
  pullClusters();
  measureClosure();
}

size_t ReflectedLightHierarchy::rerefine() {
  updateVariation();
  std::vector<PendingPair> pending;
  size_t refined = 0;
  for (size_t l = 0; l < records_.size(); ++l) {
    LinkRecord &link = records_[l];
    if (!link.alive || error(link.receiver, link.source, formFactorOf(link), link.spread) <= threshold_) continue;
    if (!canSplit(link.receiver) && !canSplit(link.source)) continue;
    link.alive = false;
    auto &incoming = links_[link.receiver];
    incoming.erase(std::find(incoming.begin(), incoming.end(), uint32_t(l)));
    splitPair(link.receiver, link.source, link.clearShaft, pending);
  }
  for (size_t l = 0; l < clusterRecords_.size(); ++l) {
    ClusterLinkRecord &link = clusterRecords_[l];
    if (!link.alive || clusterLinkError(link) <= threshold_) continue;
    if (!canSplitEnd(link.receiver) && !canSplitEnd(link.source)) continue;
    link.alive = false;
    auto &incoming = isCluster(link.receiver) ? clusterLinks_[clusterIndex(link.receiver)] : links_[link.receiver];
    const uint32_t tagged = isCluster(link.receiver) ? uint32_t(l) : uint32_t(l) | kClusterBit;
    incoming.erase(std::find(incoming.begin(), incoming.end(), tagged));
    splitPair(link.receiver, link.source, false, pending);
  }
  refined = pending.size();
  refine(std::move(pending));
  if (refined > 0) measureClosure();
  return refined;
}

bool ReflectedLightHierarchy::canSplit(uint32_t n) const {
  return mesh_.tree[n].longestEdge() >= 2 * minimumEdge_ && leaves_ + 3 <= options_.maxElements;
}

double ReflectedLightHierarchy::sizeOf(uint32_t id) const {
  if (isCluster(id)) {
    const Box3 &b = clusters_.clusters[clusterIndex(id)].bounds;
    return length(b.hi - b.lo);
  }
  return mesh_.tree[id].longestEdge();
}

double ReflectedLightHierarchy::error(uint32_t r, uint32_t s, double formFactor, double spreadOfF) const {
  // The error in the reflected radiosity of the receiver that the link
  // would make, W·m⁻² (max band).
  const Bands spread = reflected_[s] * spreadOfF + variation_[s] * formFactor;
  double worst = 0;
  for (int b = 0; b < kBandCount; ++b)
    worst = std::max(worst, std::max(scattering(r)[b], kLeastReflectance) * spread[b]);
  return worst;
}

void ReflectedLightHierarchy::splitNode(uint32_t n) {
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

bool ReflectedLightHierarchy::splitPair(uint32_t r, uint32_t s, bool clearShaft, std::vector<PendingPair> &pending) {
  thread_local std::vector<uint32_t> children, others;
  if (r == s) {
    // A cluster with itself: every pair of its children, each child with itself too.
    childrenOf(r, children);
    for (uint32_t a : children)
      for (uint32_t b : children)
        if ((a != b || isCluster(a)) && facingEnds(a, b)) pending.push_back({a, b, false});
    return true;
  }
  // The larger of the two (RenderPark's rule; splitting by which term of
  // the error dominates made more links and a worse image).
  const bool treeNodes = !isCluster(r) && !isCluster(s);
  const bool receiverFirst = treeNodes ? mesh_.tree[r].area >= mesh_.tree[s].area : sizeOf(r) >= sizeOf(s);
  const bool splitReceiver = canSplitEnd(r) && (receiverFirst || !canSplitEnd(s));
  if (!splitReceiver && !canSplitEnd(s)) return false;
  const uint32_t node = splitReceiver ? r : s;
  // Cleared shafts carry over only between tree nodes (a child's hull lies in its parent's).
  const bool clear = clearShaft && treeNodes;
  childrenOf(node, children);
  for (uint32_t child : children) {
    const uint32_t rr = splitReceiver ? child : r, ss = splitReceiver ? s : child;
    if (facingEnds(rr, ss)) pending.push_back({rr, ss, clear});
  }
  return true;
}

bool ReflectedLightHierarchy::ownsReceiver(uint32_t id) {
  return cluster::size() == 1 || id % uint32_t(cluster::size()) == uint32_t(cluster::rank());
}

void ReflectedLightHierarchy::refine(std::vector<PendingPair> pending) {
  // In batches from the back of the queue, so that the estimates held at
  // once (about 250 bytes each) stay bounded however many pairs wait.
  constexpr size_t kBatch = size_t(1) << 15;
  std::vector<LinkEstimate> estimates;
  std::vector<ClusterLinkEstimate> clusterEstimates;
  std::vector<PendingPair> batch;
  // What each pending pair is: two tree nodes; a link with a cluster end to
  // estimate; a pair no point model holds for, to split unseen; or such a
  // pair that cannot be split, taken as near field.
  enum PairKind : uint8_t { kTreeNodes, kClusterLink, kSplitUnseen, kNearField };
  std::vector<uint8_t> kind;
  std::vector<size_t> kept;
  while (!pending.empty()) {
    const size_t count = std::min(kBatch, pending.size());
    batch.assign(pending.end() - static_cast<std::ptrdiff_t>(count), pending.end());
    pending.resize(pending.size() - count);
    kind.assign(count, kTreeNodes);
    for (size_t i = 0; i < count; ++i) {
      const uint32_t r = batch[i].receiver, s = batch[i].source;
      if (!isCluster(r) && !isCluster(s)) continue;
      // A cluster with itself, or two ends whose boxes meet: no point model
      // holds, so split them; when neither can be split (a smallest cluster
      // with itself, or beside a smallest node), the near field.
      const bool splittable = canSplitEnd(r) || canSplitEnd(s);
      if (r == s || endsOverlap(hierarchyEnd(r), hierarchyEnd(s)))
        kind[i] = splittable ? kSplitUnseen : kNearField;
      else
        kind[i] = kClusterLink;
    }
    estimates.assign(count, LinkEstimate{});
    clusterEstimates.assign(count, ClusterLinkEstimate{});
    // With several MPI ranks, each estimates the pairs whose receiver it
    // owns (the links partitioned by receiver), and the estimates are then
    // shared, so that every rank takes the same decisions below and holds
    // the same links: the solution is one process's, bit for bit.
    auto owns = [&](size_t i) { return ownsReceiver(batch[i].receiver); };
    arena_.execute([&] {
      tbb::parallel_for(size_t(0), count, [&](size_t i) {
        if (!owns(i)) return;
        const uint32_t r = batch[i].receiver, s = batch[i].source;
        if (kind[i] == kTreeNodes)
          estimates[i] = estimator_.estimate(end(r), end(s), batch[i].clearShaft);
        else if (kind[i] != kSplitUnseen)
          clusterEstimates[i] = estimateClusterLink(tracer_, hierarchyEnd(r), hierarchyEnd(s), kind[i] == kNearField);
      });
    });
    if (cluster::distributed()) {
      // What the decisions read of a tree-node link (a tenth of its
      // estimate; the owner completes the shape of those kept, and shares
      // them whole below), and every cluster link's estimate.
      struct Decision {
        double formFactor, spread;
        int rays;
        bool clearShaft;
      };
      std::vector<Decision> decisions(count);
      std::vector<size_t> trees, clustered;
      for (size_t i = 0; i < count; ++i) {
        (kind[i] == kTreeNodes ? trees : clustered).push_back(i);
        const LinkEstimate &e = estimates[i];
        decisions[i] = {e.formFactor, e.spread, e.rays, e.clearShaft};
      }
      cluster::shareOwnedEntries(decisions, trees, owns);
      for (size_t i : trees)
        if (!owns(i)) {
          LinkEstimate &e = estimates[i];
          e.formFactor = decisions[i].formFactor, e.spread = decisions[i].spread;
          e.rays = decisions[i].rays, e.clearShaft = decisions[i].clearShaft;
        }
      cluster::shareOwnedEntries(clusterEstimates, clustered, owns);
    }
    kept.clear();
    for (size_t i = 0; i < count; ++i) {
      const uint32_t r = batch[i].receiver, s = batch[i].source;
      if (kind[i] == kSplitUnseen) {
        splitPair(r, s, false, pending);
        continue;
      }
      if (kind[i] != kTreeNodes) {
        const ClusterLinkEstimate &e = clusterEstimates[i];
        rays_ += e.rays;
        if (clusterLinkError(r, s, e) > threshold_ && splitPair(r, s, false, pending)) continue;
        if (e.kernelMean > 0 && e.visibility > 0) keepClusterLink(r, s, e, e.isotropic);
        continue;
      }
      rays_ += estimates[i].rays;
      if (error(r, s, estimates[i].formFactor, estimates[i].spread) > threshold_ && (canSplit(r) || canSplit(s))) {
        splitPair(r, s, estimates[i].clearShaft, pending);
        continue;
      }
      if (estimates[i].formFactor > 0) kept.push_back(i);
    }
    // Only the links kept need the source's moments.
    arena_.execute([&] {
      tbb::parallel_for(size_t(0), kept.size(), [&](size_t k) {
        const size_t i = kept[k];
        if (owns(i)) estimator_.completeShape(end(batch[i].receiver), end(batch[i].source), estimates[i]);
      });
    });
    if (cluster::distributed()) {
      // What a kept link's record takes of its completed estimate.
      struct Shape {
        ReceiverPolynomial<float> shape;
        std::array<float, 2> moments;
      };
      std::vector<Shape> shapes(count);
      for (size_t i : kept) shapes[i] = {estimates[i].shape, estimates[i].moments};
      cluster::shareOwnedEntries(shapes, kept, owns);
      for (size_t i : kept) estimates[i].shape = shapes[i].shape, estimates[i].moments = shapes[i].moments;
    }
    for (size_t i : kept) {
      const uint32_t r = batch[i].receiver, s = batch[i].source;
      links_[r].push_back(static_cast<uint32_t>(records_.size()));
      records_.push_back(
          {r, s, estimates[i].shape, estimates[i].moments, float(estimates[i].spread), estimates[i].clearShaft, true});
    }
  }
  // New leaves need the direct light at their test points, and their R.
  if (!newLeaves_.empty()) {
    initialiseNewLeaves();
    newLeaves_.clear();
  }
}

void ReflectedLightHierarchy::initialiseNewLeaves() {
  std::vector<std::pair<uint32_t, Vec3>> points;
  std::vector<Vec3> nodePoints;
  for (uint32_t n : newLeaves_)
    for (int c = 0; c < 4; ++c) {
      const MeshTreeNode &child = mesh_.tree[mesh_.tree[n].children[c]];
      if (!child.isLeaf()) continue;
      field_.testPointsOf(child, nodePoints);
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

}  // namespace radiant
