#include "mesh/mesh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mesh/patch_lattice.h"
#include "util/error.h"
#include "util/phase.h"
#include "util/timing.h"

namespace radiant {

namespace {

double cross2(double ax, double ay, double bx, double by) {
  return ax * by - ay * bx;
}

/// Bilinear point P(u, v) of a quad a=P(0,0), b=P(1,0), c=P(1,1), d=P(0,1).
Vec3 bilinear(const std::array<Vec3, 4> &q, double u, double v) {
  return q[0] * ((1 - u) * (1 - v)) + q[1] * (u * (1 - v)) + q[2] * (u * v) + q[3] * ((1 - u) * v);
}

/// Inverse of the bilinear map of a planar quad (Quílez's closed form, done in
/// the quad's plane): the (u, v) with P(u, v) = p.
void inverseBilinear(const Patch &patch, const Vec3 &p, double &u, double &v) {
  Frame frame = Frame::fromNormal(patch.normal);
  auto to2 = [&](const Vec3 &x) {
    Vec3 l = frame.toLocal(x - patch.corners[0]);
    return std::array<double, 2>{l.x, l.y};
  };
  auto b = to2(patch.corners[1]), c = to2(patch.corners[2]), d = to2(patch.corners[3]), h = to2(p);
  double ex = b[0], ey = b[1], fx = d[0], fy = d[1];
  double gx = -b[0] + c[0] - d[0], gy = -b[1] + c[1] - d[1];
  double k2 = cross2(gx, gy, fx, fy);
  double k1 = cross2(ex, ey, fx, fy) + cross2(h[0], h[1], gx, gy);
  double k0 = cross2(h[0], h[1], ex, ey);
  auto solveU = [&](double vv) {
    // Least squares along the edge direction at height v: robust whichever axis it follows.
    double rx = h[0] - fx * vv, ry = h[1] - fy * vv, sx = ex + gx * vv, sy = ey + gy * vv;
    double s2 = sx * sx + sy * sy;
    return s2 > 0 ? (rx * sx + ry * sy) / s2 : 0.0;
  };
  double scale = patch.area;
  if (std::abs(k2) <= 1e-12 * scale * scale || std::abs(k2) <= 1e-9 * std::abs(k1) * std::sqrt(scale)) {
    v = k1 != 0 ? -k0 / k1 : 0;  // a parallelogram: the map is affine
  } else {
    double w = std::sqrt(std::max(0.0, k1 * k1 - 4 * k0 * k2));
    double v1 = (-k1 - w) / (2 * k2), v2 = (-k1 + w) / (2 * k2);
    auto outside = [](double x) { return std::max({0.0, -x, x - 1}); };
    v = outside(v1) <= outside(v2) ? v1 : v2;
  }
  u = solveU(v);
}

/// Barycentric weights of `p` in triangle a, b, c (in its plane), as locate() computes them.
std::array<double, 3> barycentric(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &p) {
  const Vec3 n = cross(b - a, c - a);
  const double n2 = dot(n, n);
  const double b1 = dot(cross(p - a, c - a), n) / n2, b2 = dot(cross(b - a, p - a), n) / n2;
  return {1 - b1 - b2, b1, b2};
}

/// The face's vertex normals interpolated at `p` (a point of the face) as the
/// ray tracer does: linearly over the fan triangle (0, k, k + 1) holding it.
/// Not normalised, so that a patch's corners interpolate on to its nodes.
Vec3 vertexNormalAt(const Scene &scene, const Face &face, const Vec3 &p) {
  Vec3 best;
  double bestOutside = INFINITY;
  for (int k = 1; k + 1 < face.vertexCount; ++k) {
    const int corner[3] = {0, k, k + 1};
    const std::array<double, 3> w = barycentric(scene.positions[face.vertices[0]], scene.positions[face.vertices[k]],
                                                scene.positions[face.vertices[k + 1]], p);
    const double outside = std::max({0.0, -w[0], -w[1], -w[2]});
    if (!(outside < bestOutside)) continue;
    bestOutside = outside;
    best = Vec3{};
    for (int j = 0; j < 3; ++j) best += scene.normals[size_t(face.normals[corner[j]])] * w[j];
  }
  return best;
}

}  // namespace

std::vector<Vec3> RadiosityMesh::polygon(uint32_t element) const {
  const Element &e = elements[element];
  std::vector<Vec3> p(e.vertexCount);
  for (int k = 0; k < e.vertexCount; ++k) p[k] = nodes[e.nodes[k]];
  return p;
}

int32_t RadiosityMesh::patchAt(uint32_t face, const Vec3 &position) const {
  const int32_t first = patchOfFace[face];
  const uint32_t count = facePatchCount.empty() || first < 0 ? 1 : facePatchCount[face];
  if (first < 0 || count <= 1) return first;
  // The patch whose edges the point is furthest inside of (all patches of a
  // face share its plane and normal): robust on the cuts between them. The
  // face's grid names the few patches near the point.
  const uint32_t *candidates = nullptr;
  uint32_t candidateCount = 0;
  std::vector<uint32_t> all;
  if (face < patchGridOfFace.size() && patchGridOfFace[face] >= 0) {
    const PatchGrid &g = patchGrids[patchGridOfFace[face]];
    const Vec3 d = position - g.origin;
    const int i = std::clamp(static_cast<int>(std::floor(dot(d, g.axisU) / g.cellU)), 0, g.cellsU - 1);
    const int j = std::clamp(static_cast<int>(std::floor(dot(d, g.axisV) / g.cellV)), 0, g.cellsV - 1);
    const uint32_t cell = uint32_t(j * g.cellsU + i);
    candidates = g.patches.data() + g.cellStart[cell];
    candidateCount = g.cellStart[cell + 1] - g.cellStart[cell];
  }
  if (candidateCount == 0) {
    for (uint32_t k = 0; k < count; ++k) all.push_back(first + k);
    candidates = all.data();
    candidateCount = count;
  }
  int32_t best = first;
  double bestDepth = -INFINITY;
  for (uint32_t c = 0; c < candidateCount; ++c) {
    const uint32_t k = candidates[c] - uint32_t(first);
    const double depth = patches[first + k].depthInside(position);
    if (depth > bestDepth) bestDepth = depth, best = static_cast<int32_t>(first + k);
  }
  return best;
}

void RadiosityMesh::buildPatchLookup() {
  for (Patch &p : patches)
    for (int v = 0; v < p.vertexCount; ++v)
      p.inwardEdgeNormals[v] = normalize(cross(p.normal, p.corners[(v + 1) % p.vertexCount] - p.corners[v]));
  patchGridOfFace.assign(patchOfFace.size(), -1);
  patchGrids.clear();
  for (size_t f = 0; f < patchOfFace.size(); ++f) {
    if (patchOfFace[f] < 0 || facePatchCount.empty() || facePatchCount[f] <= 1) continue;
    const uint32_t first = static_cast<uint32_t>(patchOfFace[f]), count = facePatchCount[f];
    PatchGrid g;
    const Frame frame = Frame::fromNormal(patches[first].normal);
    g.axisU = frame.tangent, g.axisV = frame.bitangent;
    double loU = INFINITY, loV = INFINITY, hiU = -INFINITY, hiV = -INFINITY;
    const Vec3 base = patches[first].corners[0];
    for (uint32_t k = 0; k < count; ++k)
      for (int v = 0; v < patches[first + k].vertexCount; ++v) {
        const Vec3 d = patches[first + k].corners[v] - base;
        loU = std::min(loU, dot(d, g.axisU)), hiU = std::max(hiU, dot(d, g.axisU));
        loV = std::min(loV, dot(d, g.axisV)), hiV = std::max(hiV, dot(d, g.axisV));
      }
    g.origin = base + g.axisU * loU + g.axisV * loV;
    const int side = std::clamp(static_cast<int>(std::ceil(std::sqrt(double(count)))), 1, 64);
    g.cellsU = g.cellsV = side;
    g.cellU = std::max(hiU - loU, 1e-12) / side, g.cellV = std::max(hiV - loV, 1e-12) / side;
    std::vector<std::vector<uint32_t>> cells(size_t(side) * side);
    for (uint32_t k = 0; k < count; ++k) {
      double pu0 = INFINITY, pv0 = INFINITY, pu1 = -INFINITY, pv1 = -INFINITY;
      for (int v = 0; v < patches[first + k].vertexCount; ++v) {
        const Vec3 d = patches[first + k].corners[v] - g.origin;
        pu0 = std::min(pu0, dot(d, g.axisU)), pu1 = std::max(pu1, dot(d, g.axisU));
        pv0 = std::min(pv0, dot(d, g.axisV)), pv1 = std::max(pv1, dot(d, g.axisV));
      }
      // Widened by a cell's hundredth, so a point on a shared edge finds both sides.
      const int i0 = std::clamp(static_cast<int>(std::floor(pu0 / g.cellU - 0.01)), 0, side - 1);
      const int i1 = std::clamp(static_cast<int>(std::floor(pu1 / g.cellU + 0.01)), 0, side - 1);
      const int j0 = std::clamp(static_cast<int>(std::floor(pv0 / g.cellV - 0.01)), 0, side - 1);
      const int j1 = std::clamp(static_cast<int>(std::floor(pv1 / g.cellV + 0.01)), 0, side - 1);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) cells[size_t(j) * side + i].push_back(first + k);
    }
    g.cellStart.push_back(0);
    for (const auto &cell : cells) {
      g.patches.insert(g.patches.end(), cell.begin(), cell.end());
      g.cellStart.push_back(static_cast<uint32_t>(g.patches.size()));
    }
    patchGridOfFace[f] = static_cast<int32_t>(patchGrids.size());
    patchGrids.push_back(std::move(g));
  }
}

void RadiosityMesh::setShadingNormals(const Scene &scene) {
  patchCornerNormals.clear();
  nodeShadingNormals.clear();
  auto hasVertexNormals = [&](uint32_t f) {
    if (f >= scene.faces.size()) return false;
    const Face &face = scene.faces[f];
    for (int k = 0; k < face.vertexCount; ++k)
      if (face.normals[k] < 0 || size_t(face.normals[k]) >= scene.normals.size()) return false;
    return true;
  };
  // Nothing stored for a scene without vertex normals (most rooms).
  if (std::none_of(patches.begin(), patches.end(), [&](const Patch &p) { return hasVertexNormals(p.face); })) return;
  patchCornerNormals.assign(patches.size(), {});
  for (size_t p = 0; p < patches.size(); ++p) {
    const Patch &patch = patches[p];
    if (!hasVertexNormals(patch.face)) continue;
    for (int k = 0; k < patch.vertexCount; ++k) {
      const Vec3 n = vertexNormalAt(scene, scene.faces[patch.face], patch.corners[k]);
      if (isFinite(n)) patchCornerNormals[p][k] = {float(n.x), float(n.y), float(n.z)};
    }
  }
  interpolateNodeShadingNormals();
}

void RadiosityMesh::interpolateNodeShadingNormals() {
  nodeShadingNormals.clear();
  if (patchCornerNormals.empty() || patchCornerNormals.size() != patches.size()) return;
  nodeShadingNormals.assign(nodes.size(), ShadingNormal{});
  for (size_t v = 0; v < nodes.size(); ++v) {
    const Patch &patch = patches[nodePatch[v]];
    const std::array<ShadingNormal, 4> &corner = patchCornerNormals[nodePatch[v]];
    std::array<double, 4> w{};
    if (patch.vertexCount == 4) {
      double u = 0, t = 0;
      inverseBilinear(patch, nodes[v], u, t);
      w = {(1 - u) * (1 - t), u * (1 - t), u * t, (1 - u) * t};
    } else {
      const std::array<double, 3> b = barycentric(patch.corners[0], patch.corners[1], patch.corners[2], nodes[v]);
      w = {b[0], b[1], b[2], 0.0};
    }
    Vec3 n;
    for (int k = 0; k < patch.vertexCount; ++k) n += toVec3(corner[k]) * w[k];
    const double len = length(n);
    if (!(len > 0) || !std::isfinite(len)) continue;  // no vertex normals (all corners zero)
    n = n / len;
    if (dot(n, patch.normal) < 0) n = -n;  // the ray tracer's rule: on the geometric normal's side
    nodeShadingNormals[v] = {float(n.x), float(n.y), float(n.z)};
  }
}

bool RadiosityMesh::sameSmoothSurface(uint32_t a, uint32_t b) const {
  const Patch &pa = patches[nodePatch[a]], &pb = patches[nodePatch[b]];
  if (pa.material != pb.material) return false;
  if (dot(pa.normal, pb.normal) > kSmoothSurfaceCosine) return true;
  return !nodeShadingNormals.empty() && sameShadingNormal(nodeShadingNormals[a], nodeShadingNormals[b]);
}

void RadiosityMesh::markNodesOnCuts() {
  nodeOnCut.assign(nodes.size(), 0);
  if (faceCuts.empty() || nodes.empty()) return;
  // Within a millionth of the mesh's size of a cut: the cuts stop a hair short
  // of the face's edges (face_split.cpp clips them inwards by 10⁻⁷ of the
  // scene), and the nodes at their ends must count too.
  Vec3 lo = nodes[0], hi = nodes[0];
  for (const Vec3 &x : nodes)
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], x[k]), hi[k] = std::max(hi[k], x[k]);
  const double tolerance = 1e-6 * std::max(length(hi - lo), 1e-12);
  for (size_t v = 0; v < nodes.size(); ++v) {
    const std::vector<CutSegment> &cuts = faceCuts[patches[nodePatch[v]].face];
    for (const CutSegment &c : cuts) {
      const Vec3 d = c.b - c.a;
      const double l2 = dot(d, d);
      const double t = l2 > 0 ? std::clamp(dot(nodes[v] - c.a, d) / l2, 0.0, 1.0) : 0.0;
      if (length(nodes[v] - (c.a + d * t)) <= tolerance) {
        nodeOnCut[v] = 1;
        break;
      }
    }
  }
}

std::vector<int32_t> RadiosityMesh::wholeFaceElements() const {
  std::vector<int32_t> element(patchOfFace.size(), kNoElement);
  for (size_t f = 0; f < element.size(); ++f) {
    const int32_t first = patchOfFace[f];
    if (first < 0) continue;
    const uint32_t count = facePatchCount.empty() ? 1 : facePatchCount[f];
    const Patch &patch = patches[size_t(first)];
    const bool whole =
        count <= 1 && patch.elementCount == 1 &&
        (patch.treeRoot < 0 || (size_t(patch.treeRoot) < tree.size() && tree[size_t(patch.treeRoot)].isLeaf()));
    element[f] = whole ? int32_t(patch.firstElement) : kLocateElement;
  }
  return element;
}

MeshLocation RadiosityMesh::locate(uint32_t face, const Vec3 &position) const {
  const uint32_t patchIndex = uint32_t(patchAt(face, position));
  const Patch &patch = patches[patchIndex];
  MeshLocation location;
  if (patch.treeRoot >= 0) return locateInTree(patchIndex, position);
  if (patch.vertexCount == 4) {
    double u, v;
    inverseBilinear(patch, position, u, v);
    const int nU = patch.divisionsU, nV = patch.divisionsV;
    // NaN (a degenerate patch, or a corrupt solution file's) goes to 0: std::clamp
    // would pass it through, and int(NaN) indexes anywhere.
    double x = (u >= 0 ? std::min(u, 1.0) : 0.0) * nU, y = (v >= 0 ? std::min(v, 1.0) : 0.0) * nV;
    int i = std::min(nU - 1, static_cast<int>(x)), j = std::min(nV - 1, static_cast<int>(y));
    location.element = patch.firstElement + uint32_t(j * nU + i);
    location.s = std::clamp(x - i, 0.0, 1.0);
    location.t = std::clamp(y - j, 0.0, 1.0);
    return location;
  }
  // Triangle: barycentrics by areas in the patch's plane.
  const Vec3 &a = patch.corners[0], &b = patch.corners[1], &c = patch.corners[2];
  Vec3 n = cross(b - a, c - a);
  double n2 = dot(n, n);
  double b1 = dot(cross(position - a, c - a), n) / n2;
  double b2 = dot(cross(b - a, position - a), n) / n2;
  b1 = b1 >= 0 ? std::min(b1, 1.0) : 0.0;  // as std::clamp, but NaN to 0 (see above)
  b2 = b2 >= 0 ? std::min(b2, 1.0 - b1) : 0.0;
  const int d = patch.divisionsU;
  double x = b1 * d, y = b2 * d;
  int i = std::min(d - 1, static_cast<int>(x)), j = std::min(d - 1 - i, static_cast<int>(y));
  double fi = std::clamp(x - i, 0.0, 1.0), fj = std::clamp(y - j, 0.0, 1.0);
  bool upper = fi + fj > 1 && i + j <= d - 2;
  uint32_t rowOffset = uint32_t(j * (2 * d - j));
  if (upper) {
    location.element = patch.firstElement + rowOffset + uint32_t(d - j + i);
    location.t = 1 - fi;  // weights: node0 (i+1, j) 1−s−t, node1 (i+1, j+1) s, node2 (i, j+1) t
    location.s = fi + fj - 1;
  } else {
    if (fi + fj > 1) {  // on the patch's far edge: project back onto the lower element
      double excess = (fi + fj - 1) / 2;
      fi -= excess;
      fj -= excess;
    }
    location.element = patch.firstElement + rowOffset + uint32_t(i);
    location.s = fi;
    location.t = fj;
  }
  return location;
}

MeshLocation RadiosityMesh::locateInTree(uint32_t patchIndex, const Vec3 &position) const {
  const Patch &patch = patches[patchIndex];
  // Parameters in the patch, then down the tree, re-expressing them in each child.
  double a, b;
  if (patch.vertexCount == 4) {
    inverseBilinear(patch, position, a, b);
  } else {
    const Vec3 &p0 = patch.corners[0], &p1 = patch.corners[1], &p2 = patch.corners[2];
    Vec3 n = cross(p1 - p0, p2 - p0);
    double n2 = dot(n, n);
    a = dot(cross(position - p0, p2 - p0), n) / n2;
    b = dot(cross(p1 - p0, position - p0), n) / n2;
  }
  int32_t node = patch.treeRoot;
  // Every node of a patch's tree has the patch's corner count.
  const bool compact = treeDescent.size() == tree.size();
  auto childrenOf = [&](int32_t n) -> const std::array<int32_t, 4> & {
    return compact ? treeDescent[size_t(n)] : tree[size_t(n)].children;
  };
  if (compact && patchIndex < treeShortcutOfPatch.size() && treeShortcutOfPatch[patchIndex].level > 0) {
    // Straight to the node of the shortcut's cell, with (a, b) re-expressed
    // in it as the descent below would: scaling by 2^depth and dropping the
    // integer part are exact, so is each of its halvings.
    const TreeShortcut &shortcut = treeShortcutOfPatch[patchIndex];
    const int cells = 1 << shortcut.level;
    a = a >= 0 ? std::min(a, 1.0) : 0.0, b = b >= 0 ? std::min(b, 1.0) : 0.0;  // NaN to 0, as locate()
    const int i = std::min(cells - 1, int(a * cells)), j = std::min(cells - 1, int(b * cells));
    const std::array<int32_t, 2> &cell = treeShortcutNodes[shortcut.first + size_t(j) * size_t(cells) + size_t(i)];
    node = cell[0];
    const double scale = double(int64_t(1) << cell[1]);
    const double sa = a * scale, sb = b * scale;
    const double ia = std::min(std::floor(sa), scale - 1), ib = std::min(std::floor(sb), scale - 1);
    a = sa - ia, b = sb - ib;
  }
  while (childrenOf(node)[0] >= 0) {
    const std::array<int32_t, 4> &children = childrenOf(node);
    if (patch.vertexCount == 4) {
      a = std::clamp(a, 0.0, 1.0), b = std::clamp(b, 0.0, 1.0);
      int i = a >= 0.5 ? 1 : 0, j = b >= 0.5 ? 1 : 0;
      node = children[j == 0 ? i : 3 - i];  // children: (0,0), (1,0), (1,1), (0,1)
      a = 2 * a - i, b = 2 * b - j;
    } else {
      a = std::clamp(a, 0.0, 1.0), b = std::clamp(b, 0.0, 1.0 - a);
      if (a >= 0.5)
        node = children[1], a = 2 * a - 1, b = 2 * b;
      else if (b >= 0.5)
        node = children[2], a = 2 * a, b = 2 * b - 1;
      else if (a + b <= 0.5)
        node = children[0], a = 2 * a, b = 2 * b;
      else {
        double s = 2 * a + 2 * b - 1, u = 1 - 2 * a;  // middle child (mab, mbc, mac)
        node = children[3], a = s, b = u;
      }
    }
  }
  MeshLocation location;
  location.element = static_cast<uint32_t>(compact ? treeDescent[size_t(node)][1] : tree[size_t(node)].element);
  location.s = std::clamp(a, 0.0, 1.0);
  location.t = std::clamp(b, 0.0, patch.vertexCount == 4 ? 1.0 : 1.0 - location.s);
  return location;
}

std::array<double, 4> RadiosityMesh::nodeWeights(const MeshLocation &l) const {
  if (elements[l.element].vertexCount == 4) return {(1 - l.s) * (1 - l.t), l.s * (1 - l.t), l.s * l.t, (1 - l.s) * l.t};
  return {1 - l.s - l.t, l.s, l.t, 0.0};
}

void appendPatchLattice(const Patch &patch, uint32_t patchIndex, RadiosityMesh &mesh) {
  auto addElement = [&](int count, std::array<uint32_t, 4> nodes) {
    Element e;
    e.patch = patchIndex;
    e.vertexCount = count;
    e.nodes = nodes;
    Vec3 sum;
    for (int k = 0; k < count; ++k) sum += mesh.nodes[nodes[k]];
    e.centre = sum / count;
    for (int k = 1; k + 1 < count; ++k)
      e.area += 0.5 * length(cross(mesh.nodes[nodes[k]] - mesh.nodes[nodes[0]],
                                   mesh.nodes[nodes[k + 1]] - mesh.nodes[nodes[0]]));
    mesh.elements.push_back(e);
  };
  if (patch.vertexCount == 4) {
    const int nU = patch.divisionsU, nV = patch.divisionsV;
    for (int j = 0; j <= nV; ++j)
      for (int i = 0; i <= nU; ++i) mesh.nodes.push_back(bilinear(patch.corners, double(i) / nU, double(j) / nV));
    auto node = [&](int i, int j) { return patch.firstNode + uint32_t(j * (nU + 1) + i); };
    for (int j = 0; j < nV; ++j)
      for (int i = 0; i < nU; ++i) addElement(4, {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
  } else {
    const int n = patch.divisionsU;
    const Vec3 &a = patch.corners[0], &b = patch.corners[1], &c = patch.corners[2];
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n - j; ++i) mesh.nodes.push_back(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
    auto node = [&](int i, int j) { return patch.firstNode + uint32_t(j * (n + 1) - j * (j - 1) / 2 + i); };
    // Row j: its n − j lower triangles, then its n − j − 1 upper ones (the order locate() assumes).
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n - j; ++i) addElement(3, {node(i, j), node(i + 1, j), node(i, j + 1), 0});
      for (int i = 0; i < n - j - 1; ++i) addElement(3, {node(i + 1, j), node(i + 1, j + 1), node(i, j + 1), 0});
    }
  }
}

RadiosityMesh buildMesh(const Scene &scene, const MeshOptions &options) {
  Phase phase("meshing", scene.faces.size());
  const ScopedTiming timing("meshing: the patches");
  RadiosityMesh mesh;
  double edge = options.maxEdgeLength;
  if (!(edge > 0)) {
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    for (const Vec3 &p : scene.positions)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    edge = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-9}) * options.defaultEdgeFraction;
  }

  // The polygons that become patches: each face whole, or the quads and
  // triangles of its visible pieces when it was cut (mesh/face_split.h).
  const std::vector<FaceSplit> *splits = options.faceSplits;
  std::vector<std::vector<std::vector<Vec3>>> polygons(scene.faces.size());
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    if (splits && (*splits)[f].split()) {
      for (const std::vector<Vec3> &piece : (*splits)[f].pieces)
        for (std::vector<Vec3> &p : convexToPatches(piece)) polygons[f].push_back(std::move(p));
      continue;
    }
    const Face &face = scene.faces[f];
    std::vector<Vec3> p;
    for (int k = 0; k < face.vertexCount; ++k) p.push_back(scene.positions[face.vertices[k]]);
    polygons[f].push_back(std::move(p));
  }

  // First the counts, so an absurd request fails before any allocation.
  size_t totalElements = 0;
  std::vector<std::vector<std::array<int, 2>>> divisions(scene.faces.size());
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    for (const std::vector<Vec3> &poly : polygons[f]) {
      auto corner = [&](int k) { return poly[k]; };
      auto steps = [&](double length) {
        // In double first: a tiny mesh-size gives counts beyond int, whose
        // cast would wrap to one element per face without a word.
        const double n = std::ceil(length / edge - 1e-9);
        if (!(n <= double(options.maxElements)))
          throw InputError(InputLocation::ofParameter("mesh-size"),
                           fmt::format("the mesh would have more than {} elements (element edge {:.4g} m); "
                                       "choose a larger mesh-size or raise max-elements",
                                       options.maxElements, edge));
        return std::max(1, static_cast<int>(n));
      };
      if (poly.size() == 4) {
        int nU = steps(std::max(length(corner(1) - corner(0)), length(corner(2) - corner(3))));
        int nV = steps(std::max(length(corner(3) - corner(0)), length(corner(2) - corner(1))));
        divisions[f].push_back({nU, nV});
        totalElements += size_t(nU) * nV;
      } else {
        int n = steps(
            std::max({length(corner(1) - corner(0)), length(corner(2) - corner(1)), length(corner(0) - corner(2))}));
        divisions[f].push_back({n, n});
        totalElements += size_t(n) * n;
      }
    }
    if (totalElements > options.maxElements)
      throw InputError(InputLocation::ofParameter("mesh-size"),
                       fmt::format("the mesh would have more than {} elements (element edge {:.4g} m); "
                                   "choose a larger mesh-size or raise max-elements",
                                   options.maxElements, edge));
  }

  mesh.patchOfFace.assign(scene.faces.size(), -1);
  mesh.facePatchCount.assign(scene.faces.size(), 0);
  if (splits) {
    mesh.faceCuts.resize(scene.faces.size());
    for (size_t f = 0; f < scene.faces.size(); ++f) mesh.faceCuts[f] = (*splits)[f].cuts;
  }
  mesh.elements.reserve(totalElements);
  for (size_t f = 0; f < scene.faces.size(); ++f, phase.advance())
    for (size_t piece = 0; piece < polygons[f].size(); ++piece) {
      const Face &face = scene.faces[f];
      const std::vector<Vec3> &poly = polygons[f][piece];
      Patch patch;
      patch.face = static_cast<uint32_t>(f);
      patch.material = face.material;
      patch.object = face.object;
      patch.vertexCount = static_cast<int>(poly.size());
      for (int k = 0; k < patch.vertexCount; ++k) patch.corners[k] = poly[k];
      patch.normal = scene.faceNormal(face);
      patch.area = 0;
      for (int k = 1; k + 1 < patch.vertexCount; ++k)
        patch.area += 0.5 * length(cross(poly[k] - poly[0], poly[k + 1] - poly[0]));
      if (polygons[f].size() == 1 && !(splits && (*splits)[f].split())) patch.area = scene.faceArea(face);
      patch.divisionsU = divisions[f][piece][0];
      patch.divisionsV = divisions[f][piece][1];
      patch.firstElement = static_cast<uint32_t>(mesh.elements.size());
      patch.firstNode = static_cast<uint32_t>(mesh.nodes.size());
      const uint32_t patchIndex = static_cast<uint32_t>(mesh.patches.size());
      appendPatchLattice(patch, patchIndex, mesh);
      patch.elementCount = static_cast<uint32_t>(mesh.elements.size()) - patch.firstElement;
      patch.nodeCount = static_cast<uint32_t>(mesh.nodes.size()) - patch.firstNode;
      mesh.nodePatch.resize(mesh.nodes.size(), patchIndex);
      if (mesh.patchOfFace[f] < 0) mesh.patchOfFace[f] = static_cast<int32_t>(patchIndex);
      ++mesh.facePatchCount[f];
      mesh.patches.push_back(patch);
    }
  mesh.markNodesOnCuts();
  mesh.setShadingNormals(scene);
  if (options.crossPatchTVertices) mesh.addCrossPatchTVertices();
  mesh.buildPatchLookup();
  return mesh;
}

}  // namespace radiant
