// Importance for --importance (Smits, Arvo & Salesin 1992): the visual
// importance from the camera, its propagation over the links, the oracle's
// weight. The derivation is in importance.h.
#include "radiosity/importance.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace radiant {

namespace {

/// Inside the convex polygon (in the plane of `normal`), edges included with
/// a tolerance of `slack` metres, whichever way the polygon winds.
bool insidePolygon(const Vec3 &p, const ImportanceNodeShape &shape, const Vec3 &normal, double slack) {
  const auto &c = shape.corners;
  const double winding = dot(cross(c[1] - c[0], c[2] - c[0]), normal) >= 0 ? 1.0 : -1.0;
  for (int k = 0; k < shape.vertexCount; ++k) {
    const Vec3 &a = c[k], &b = c[(k + 1) % shape.vertexCount];
    Vec3 edge = b - a;
    double edgeLength = length(edge);
    if (edgeLength <= 0) continue;
    // Signed distance of p from the edge's line, positive inside.
    if (winding * dot(cross(edge, p - a), normal) / edgeLength < -slack) return false;
  }
  return true;
}

Vec3 centreOf(const ImportanceNodeShape &shape) {
  Vec3 c;
  for (int k = 0; k < shape.vertexCount; ++k) c += shape.corners[k];
  return c / shape.vertexCount;
}

}  // namespace

VisualImportance::VisualImportance(const RayTracer &tracer, const RadiosityMesh &mesh, const ImportanceView &view) {
  const int height = std::max(1, view.resolution);
  const int width = std::clamp(static_cast<int>(std::lround(height * view.aspect)), 1, 16 * height);
  pixels_ = size_t(width) * height;
  hitsOf_.resize(mesh.patches.size());
  pixelCount_.assign(mesh.patches.size(), 0);
  largest_.assign(mesh.patches.size(), 0.0);
  // One ray through each pixel centre: every pixel weighs the same, as in the
  // image's mean (the measurement M). Deterministic, so the solve stays so.
  PinholeCamera camera(view.camera, width, height);
  // Square pixels of side 2 tan(fov/2) / height on the image plane at distance 1.
  const Vec3 forward = normalize(view.camera.target - view.camera.eye);
  const double pixelSide = pixelAngle(view.camera, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      Hit hit;
      if (!tracer.intersect(ray, hit)) continue;
      // The solution is the front's radiosity; a back face seen shows none of it.
      if (dot(ray.direction, hit.geometricNormal) >= 0) continue;
      if (hit.face >= mesh.patchOfFace.size() || mesh.patchOfFace[hit.face] < 0) continue;
      const uint32_t patch = static_cast<uint32_t>(mesh.patchOfFace[hit.face]);
      // The pixel's footprint: its solid angle (side² cos³θ) at distance r, over the surface's cosine.
      const double cosCamera = dot(ray.direction, forward);
      const double cosSurface = std::max(1e-6, -dot(ray.direction, hit.geometricNormal));
      const double footprint =
          pixelSide * pixelSide * cosCamera * cosCamera * cosCamera * hit.distance * hit.distance / cosSurface;
      const double density = 1.0 / (double(pixels_) * footprint);
      hitsOf_[patch].push_back({hit.position, density});
      ++pixelCount_[patch];
      largest_[patch] = std::max(largest_[patch], density);
      ++hits_;
      visibleArea_ += footprint;
    }
}

void VisualImportance::grow(uint32_t node) {
  if (node >= pixelCount_.size()) {
    pixelCount_.resize(node + 1, 0);
    largest_.resize(node + 1, 0.0);
    hitsOf_.resize(node + 1);
  }
}

void VisualImportance::split(uint32_t parent, const std::array<uint32_t, 4> &children,
                             const std::array<ImportanceNodeShape, 4> &shapes, const Vec3 &normal) {
  for (uint32_t child : children) grow(child);
  grow(parent);
  std::vector<PixelHit> hits = std::move(hitsOf_[parent]);
  hitsOf_[parent] = {};
  const double slack = 1e-9 * std::sqrt(shapes[0].area + shapes[1].area + shapes[2].area + shapes[3].area);
  for (const PixelHit &h : hits) {
    // First child containing it (a point on a shared edge goes to one child
    // only); round-off outside all of them: the nearest centre.
    int chosen = -1;
    for (int k = 0; k < 4 && chosen < 0; ++k)
      if (insidePolygon(h.position, shapes[k], normal, slack)) chosen = k;
    if (chosen < 0) {
      double best = INFINITY;
      for (int k = 0; k < 4; ++k) {
        double d = length(h.position - centreOf(shapes[k]));
        if (d < best) best = d, chosen = k;
      }
    }
    const uint32_t child = children[chosen];
    hitsOf_[child].push_back(h);
    ++pixelCount_[child];
    largest_[child] = std::max(largest_[child], h.density);
  }
}

int propagateImportance(const ImportanceGraph &g, std::vector<Bands> &density, double tolerance, int maxSweeps,
                        std::vector<Bands> *largestReceived) {
  const size_t nodes = g.children.size();
  const size_t oldSize = density.size();
  density.resize(nodes);
  for (size_t n = oldSize; n < nodes; ++n) density[n] = Bands(g.visual[n] / g.area[n]);
  std::vector<Bands> weighted(nodes), gathered(nodes);  // ⟨ρŶ⟩ and G per node

  // Leaves: ρŶ from Ŷ; inner nodes: area averages of their children (pull).
  auto pull = [&](auto &self, uint32_t n) -> void {
    if (g.children[n][0] < 0) {
      weighted[n] = g.reflectance[n] * density[n];
      return;
    }
    Bands y(0.0), w(0.0);
    for (int32_t c : g.children[n]) {
      self(self, uint32_t(c));
      y += density[c] * (g.area[c] / g.area[n]);
      w += weighted[c] * (g.area[c] / g.area[n]);
    }
    density[n] = y;
    weighted[n] = w;
  };
  for (uint32_t root = 0; root < g.roots; ++root) pull(pull, root);

  double change = 0, largest = 0;
  auto pushPull = [&](auto &self, uint32_t n, const Bands &down) -> void {
    const Bands received = down + gathered[n];
    if (g.children[n][0] < 0) {
      const double direct = g.visual[n] / g.area[n];
      const Bands y = Bands(direct) + received;
      change = std::max({change, (y - density[n]).max(), (density[n] - y).max()});
      largest = std::max(largest, received.max());
      density[n] = y;
      weighted[n] = g.reflectance[n] * y;
      return;
    }
    Bands y(0.0), w(0.0);
    for (int32_t c : g.children[n]) {
      self(self, uint32_t(c), received);
      y += density[c] * (g.area[c] / g.area[n]);
      w += weighted[c] * (g.area[c] / g.area[n]);
    }
    density[n] = y;
    weighted[n] = w;
  };

  // Gather at the sources, in link order (deterministic): importance flows
  // from a link's receiver back to its source with F(r ← s) A_r / A_s = F(s ← r).
  auto gather = [&] {
    std::fill(gathered.begin(), gathered.end(), Bands(0.0));
    for (const ImportanceGraph::Link &l : g.links)
      gathered[l.source] += weighted[l.receiver] * (l.formFactor * g.area[l.receiver] / g.area[l.source]);
  };
  int sweeps = 0;
  while (sweeps < maxSweeps) {
    gather();
    change = largest = 0;
    for (uint32_t root = 0; root < g.roots; ++root) pushPull(pushPull, root, Bands(0.0));
    ++sweeps;
    if (!(largest > 0) || change <= tolerance * largest) break;
  }

  if (largestReceived) {
    // What each leaf receives, Ŷ − R/A, and its maximum over every subtree.
    gather();
    largestReceived->assign(nodes, Bands(0.0));
    auto maxima = [&](auto &self, uint32_t n, const Bands &down) -> Bands {
      const Bands received = down + gathered[n];
      Bands most = received;
      if (g.children[n][0] >= 0) {
        most = Bands(0.0);
        for (int32_t c : g.children[n]) {
          const Bands m = self(self, uint32_t(c), received);
          for (int b = 0; b < kBandCount; ++b) most[b] = std::max(most[b], m[b]);
        }
      }
      (*largestReceived)[n] = most;
      return most;
    };
    for (uint32_t root = 0; root < g.roots; ++root) maxima(maxima, root, Bands(0.0));
  }
  return sweeps;
}

ImportanceRefinement::ImportanceRefinement(const RayTracer &tracer, const RadiosityMesh &mesh,
                                           const ImportanceView &view)
    : visual_(tracer, mesh, view) {
  if (!(visual_.totalFraction() > 0))
    throw InputError(InputLocation::ofParameter("importance"),
                     "the camera sees the front of no surface, so no surface is important; check --eye and --target");
  for (const Patch &p : mesh.patches) area_.push_back(p.area);
  reference_ = visual_.totalFraction() / visual_.visibleArea();
  for (uint32_t n = 0; n < area_.size(); ++n) density_.push_back(Bands(visual_.fraction(n) / area_[n]));
  received_.assign(area_.size(), Bands(0.0));
}

void ImportanceRefinement::split(uint32_t parent, const std::array<uint32_t, 4> &children,
                                 const std::array<ImportanceNodeShape, 4> &shapes, const Vec3 &normal) {
  visual_.split(parent, children, shapes, normal);
  const uint32_t last = *std::max_element(children.begin(), children.end());
  if (density_.size() <= last) {
    density_.resize(last + 1);
    received_.resize(last + 1);
    area_.resize(last + 1);
  }
  // The parent was a leaf, so what it received over links is a density over
  // all of it: the children inherit that, on top of the pixels each one shows.
  for (int k = 0; k < 4; ++k) {
    area_[children[k]] = shapes[k].area;
    received_[children[k]] = received_[parent];
    density_[children[k]] = Bands(visual_.fraction(children[k]) / shapes[k].area) + received_[parent];
  }
}

double ImportanceRefinement::weightedRadiosity(uint32_t receiver, const Bands &sourceRadiosity) const {
  return (sourceRadiosity * (Bands(visual_.largestDensity(receiver)) + received_[receiver])).max() / reference_;
}

int ImportanceRefinement::propagate(ImportanceGraph graph, double tolerance, int maxSweeps) {
  graph.visual.resize(graph.children.size());
  for (uint32_t n = 0; n < graph.visual.size(); ++n) graph.visual[n] = visual_.fraction(n);
  return propagateImportance(graph, density_, tolerance, maxSweeps, &received_);
}

SolutionImportance solutionImportance(const RayTracer &tracer, const Solution &s, const ImportanceView &view,
                                      double tolerance, int maxSweeps) {
  const RadiosityMesh &mesh = s.mesh;
  VisualImportance visual(tracer, mesh, view);
  ImportanceGraph g;
  g.roots = static_cast<uint32_t>(mesh.patches.size());
  for (uint32_t p = 0; p < g.roots; ++p)
    if (mesh.patches[p].treeRoot != int32_t(p))
      throw InputError(InputLocation{"solution"},
                       "importance needs a hierarchical solution (patch p rooted at node p)");
  const size_t nodes = mesh.tree.size();
  g.children.resize(nodes);
  g.area.resize(nodes);
  g.reflectance.assign(nodes, Bands(0.0));
  for (uint32_t n = 0; n < nodes; ++n) {
    const MeshTreeNode &t = mesh.tree[n];
    g.children[n] = t.children;
    g.area[n] = t.area;
    if (t.element >= 0) g.reflectance[n] = s.reflectance[size_t(t.element)];
    if (t.isLeaf()) continue;
    std::array<ImportanceNodeShape, 4> shapes;
    std::array<uint32_t, 4> children;
    for (int k = 0; k < 4; ++k) {
      const MeshTreeNode &c = mesh.tree[size_t(t.children[k])];
      children[k] = static_cast<uint32_t>(t.children[k]);
      shapes[k] = {c.vertexCount, c.corners, c.area};
    }
    visual.split(n, children, shapes, mesh.patches[t.patch].normal);
  }
  g.visual.resize(nodes);
  for (uint32_t n = 0; n < nodes; ++n) g.visual[n] = visual.fraction(n);
  for (const Link &l : s.links) g.links.push_back({l.receiver, l.source, double(l.formFactor)});
  SolutionImportance out;
  out.visual = g.visual;
  propagateImportance(g, out.density, tolerance, maxSweeps);
  return out;
}

}  // namespace radiant
