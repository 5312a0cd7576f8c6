#include "render/secondary_sources.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

#include "radiosity/form_factor.h"
#include "radiosity/solution_query.h"
#include "util/error.h"
#include "util/sampling.h"

namespace radiant {

namespace {

/// Above this many receiver × source-element pairs that no tree can
/// coarsen (patches meshed as uniform grids) the removal would take
/// minutes; the user should select fewer sources.
constexpr double kMaxLeafPairs = 2e8;

/// A piece of a selected patch as the removal sees it: an element, or on a
/// patch refined as a tree (hierarchical solvers) an inner node with its
/// leaves' area-weighted mean and its children.
struct SourcePiece {
  uint32_t patch = 0;
  Vec3 centre;        ///< the polygon's centroid (finishPiece)
  double radius = 0;  ///< the farthest corner from the centre
  double area = 0;
  std::vector<Vec3> polygon;
  Bands reflected;
  std::array<int32_t, 4> children{-1, -1, -1, -1};  ///< into the pieces; −1: a leaf
};

/// A tree patch's pieces, its root first (at the index pieces had on
/// entry), each node before its children. A node's value is its leaves'
/// area-weighted mean over their own areas (a root's face area can differ
/// from the sum of its leaves' by round-off). Throws on a tree deeper than
/// any the solver builds (a damaged solution file).
void addTreePieces(const Solution &s, int32_t root, std::vector<SourcePiece> &pieces) {
  constexpr int kMaxDepth = kMaxSolutionTreeDepth;  // readSolution refuses deeper trees, naming the file
  const size_t first = pieces.size();
  // Pre-order with an explicit stack: (tree node, its piece's parent piece, depth).
  struct Pending {
    int32_t node, parent, slot, depth;
  };
  std::vector<Pending> stack{{root, -1, 0, 0}};
  while (!stack.empty()) {
    const Pending at = stack.back();
    stack.pop_back();
    if (at.depth > kMaxDepth)
      throw InputError(InputLocation{"solution"},
                       fmt::format("a patch's subdivision tree is deeper than {}", kMaxDepth));
    const MeshTreeNode &n = s.mesh.tree[size_t(at.node)];
    const int32_t index = int32_t(pieces.size());
    SourcePiece piece;
    piece.patch = n.patch;
    piece.polygon.assign(n.corners.begin(), n.corners.begin() + n.vertexCount);
    if (n.isLeaf()) piece.area = n.area, piece.reflected = reflectedRadiosity(s, uint32_t(n.element)) * n.area;
    pieces.push_back(std::move(piece));
    if (at.parent >= 0) pieces[size_t(at.parent)].children[size_t(at.slot)] = index;
    if (n.isLeaf()) continue;
    for (int c = 3; c >= 0; --c)
      if (n.children[size_t(c)] >= 0) stack.push_back({n.children[size_t(c)], index, c, at.depth + 1});
  }
  // Children come after their parents: one backward pass sums Σ A·(B − E)
  // and Σ A upwards, then turns the sums into means.
  for (size_t i = pieces.size(); i-- > first;) {
    SourcePiece &piece = pieces[i];
    if (piece.children[0] < 0) continue;
    piece.area = 0, piece.reflected = Bands(0.0);
    for (int32_t c : piece.children)
      if (c >= 0) piece.area += pieces[size_t(c)].area, piece.reflected += pieces[size_t(c)].reflected;
  }
  for (size_t i = first; i < pieces.size(); ++i)
    pieces[i].reflected = pieces[i].area > 0 ? pieces[i].reflected / pieces[i].area : Bands(0.0);
}

/// A node's radiosity as a receiver at x gathers it: its children's means
/// weighted by the point-to-area kernel from x, not by area alone, so that
/// where R and the kernel vary together over the node (a wall brighter
/// near the receiver) the node is not taken as its plain mean.
Bands valueSeenFrom(const std::vector<SourcePiece> &pieces, const SourcePiece &node, const Vec3 &x, const Vec3 &n,
                    const Vec3 &nk) {
  if (node.children[0] < 0) return node.reflected;
  Bands sum(0.0);
  double weights = 0;
  for (int32_t c : node.children) {
    if (c < 0) continue;
    const SourcePiece &child = pieces[size_t(c)];
    const Vec3 d = child.centre - x;
    const double r2 = dot(d, d), cosines = std::max(0.0, dot(d, n)) * std::max(0.0, -dot(d, nk));
    const double w = child.area * cosines / (r2 * (r2 + child.area * kInvPi));
    sum += child.reflected * w, weights += w;
  }
  return weights > 0 ? sum / weights : node.reflected;
}

void finishPiece(SourcePiece &piece) {
  piece.centre = polygonCentroid(piece.polygon);
  for (const Vec3 &c : piece.polygon) piece.radius = std::max(piece.radius, length(c - piece.centre));
}

}  // namespace

const ParameterTable &secondarySourceParameters() {
  static const ParameterTable table = {
      {"sources", ParameterType::Integer, "4",
       "sample this many patches, the brightest reflectors, per pixel like emitters (Kok & Jansen 1991)", 0, 100000},
      {"source-fraction",
       ParameterType::Real,
       "0",
       "instead of sources (when > 0): the fewest patches carrying this fraction of the reflected power",
       0,
       1,
       {},
       "",
       "sources"},
      {"source-visibility-grid", ParameterType::Integer, "2",
       "the visibility of each form factor removed from the interpolated light, from grid × grid points on the "
       "source element",
       1, 16},
  };
  return table;
}

SecondarySourceOptions SecondarySourceOptions::from(const Parameters &parameters) {
  SecondarySourceOptions o;
  o.count = int(parameters.integer("sources"));
  o.fraction = parameters.real("source-fraction");
  o.visibilityGrid = int(parameters.integer("source-visibility-grid"));
  o.origin = parameters.origin(o.fraction > 0 ? "source-fraction" : "sources");
  return o;
}

SecondarySources::SecondarySources(const RayTracer &tracer, const Solution &solution,
                                   const SecondarySourceOptions &options, double openingRatio)
    : solution_(solution) {
  const RadiosityMesh &mesh = solution.mesh;
  std::vector<double> power(mesh.patches.size(), 0.0);
  double total = 0;
  for (uint32_t e = 0; e < mesh.elements.size(); ++e) {
    double p = reflectedRadiosity(solution, e).average() * mesh.elements[e].area;
    power[mesh.elements[e].patch] += p;
    total += p;
  }
  std::vector<uint32_t> order(mesh.patches.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return power[a] > power[b]; });
  double selected = 0;
  for (uint32_t p : order) {
    if (power[p] <= 0) break;
    if (options.fraction > 0 ? selected >= options.fraction * total
                             : patches_.size() >= size_t(std::max(0, options.count)))
      break;
    patches_.push_back(p);
    selected += power[p];
  }
  powerFraction_ = total > 0 ? selected / total : 0;
  double running = 0;
  for (uint32_t p : patches_) {
    probability_.push_back(power[p] / selected);
    running += probability_.back();
    cumulative_.push_back(running);
  }
  if (!cumulative_.empty()) cumulative_.back() = 1.0;
  pdfAreaOfPatch_.assign(mesh.patches.size(), 0.0);
  for (size_t j = 0; j < patches_.size(); ++j)
    pdfAreaOfPatch_[patches_[j]] = probability_[j] / mesh.patches[patches_[j]].area;
  computeRemovedRadiosity(tracer, std::max(1, options.visibilityGrid), openingRatio, options.origin);
}

void SecondarySources::computeRemovedRadiosity(const RayTracer &tracer, int grid, double openingRatio,
                                               const InputLocation &origin) {
  const RadiosityMesh &mesh = solution_.mesh;
  const Solution &s = solution_;
  // The selected patches' pieces, with their polygons and values, once:
  // as trees where the solution refined them as trees.
  std::vector<SourcePiece> pieces;
  std::vector<int32_t> roots;
  size_t leaves = 0;
  for (uint32_t p : patches_) {
    const Patch &patch = mesh.patches[p];
    if (patch.treeRoot >= 0) {
      roots.push_back(int32_t(pieces.size()));
      addTreePieces(s, patch.treeRoot, pieces);
      continue;
    }
    for (uint32_t k = 0; k < patch.elementCount; ++k) {
      const uint32_t e = patch.firstElement + k;
      roots.push_back(int32_t(pieces.size()));
      pieces.push_back({p, {}, 0, mesh.elements[e].area, mesh.polygon(e), reflectedRadiosity(s, e)});
    }
  }
  for (SourcePiece &piece : pieces) finishPiece(piece), leaves += piece.children[0] < 0;
  // What no tree can coarsen (grid patches' elements, or every leaf when the
  // opening ratio is 0) is paired with every receiver: refuse minutes of it.
  const size_t unopened = openingRatio > 0 ? roots.size() : leaves;
  if (double(unopened) * double(mesh.elements.size()) > kMaxLeafPairs)
    throw InputError(origin,
                     fmt::format("{} source elements × {} receivers is too many form factors; select fewer sources",
                                 unopened, mesh.elements.size()));
  sourceElements_ = leaves;
  removed_.assign(mesh.elements.size(), Bands(0.0));
  std::vector<uint32_t> evaluated(mesh.elements.size(), 0);
  tbb::parallel_for(size_t(0), mesh.elements.size(), [&](size_t i) {
    const Element &receiver = mesh.elements[i];
    const Vec3 &n = mesh.normalOf(uint32_t(i));
    std::vector<int32_t> stack(roots.rbegin(), roots.rend());
    Bands gathered(0.0);
    while (!stack.empty()) {
      const SourcePiece &source = pieces[size_t(stack.back())];
      stack.pop_back();
      if (source.patch == receiver.patch) continue;
      const Vec3 &nk = mesh.patches[source.patch].normal;
      // Behind the source's plane: its front faces away (all of it: the
      // pieces of a patch share its plane).
      if (dot(receiver.centre - source.centre, nk) <= 0) continue;
      // A piece seen under a wide angle is taken as its children (Barnes
      // & Hut's opening test): near the receiver the leaves themselves,
      // far away a node's mean, whose form factor varies little over it.
      if (source.children[0] >= 0 && source.radius > openingRatio * length(receiver.centre - source.centre)) {
        for (int c = 3; c >= 0; --c)
          if (source.children[size_t(c)] >= 0) stack.push_back(source.children[size_t(c)]);
        continue;
      }
      ++evaluated[i];
      // The part of the source in front of the receiver, its exact factor,
      // and its visible fraction from grid × grid stratified points on that part.
      VisibilitySamples samples;
      samples.grid = grid;
      const double f = visibleFormFactor(tracer, receiver.centre, n, n, source.polygon, nk, samples);
      if (f <= 0) continue;
      gathered += valueSeenFrom(pieces, source, receiver.centre, n, nk) * f;
    }
    removed_[i] = s.reflectance[i] * gathered;
  });
  double sum = 0;
  for (uint32_t count : evaluated) sum += count;
  piecesPerReceiver_ = evaluated.empty() ? 0 : sum / double(evaluated.size());
}

Bands SecondarySources::radiance(uint32_t element) const {
  return reflectedRadiosity(solution_, element) * kInvPi;
}

bool SecondarySources::sample(double uSelect, double u1, double u2, SecondarySourceSample &out) const {
  if (patches_.empty()) return false;
  size_t j = std::upper_bound(cumulative_.begin(), cumulative_.end(), uSelect) - cumulative_.begin();
  j = std::min(j, patches_.size() - 1);
  const Patch &patch = solution_.mesh.patches[patches_[j]];
  out.position = samplePlanarPolygon(patch.corners.data(), patch.vertexCount, u1, u2);
  out.normal = patch.normal;
  MeshLocation location = solution_.mesh.locate(patch.face, out.position);
  out.radiance = radiance(location.element);
  out.pdfArea = probability_[j] / patch.area;
  return true;
}

}  // namespace radiant
