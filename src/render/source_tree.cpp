#include "render/source_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiant {

namespace {

Vec3 lower(const Vec3 &a, const Vec3 &b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
Vec3 upper(const Vec3 &a, const Vec3 &b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

std::vector<Bands> displayRadiosities(const Solution &solution) {
  std::vector<Bands> radiosity(solution.elementCount());
  for (uint32_t e = 0; e < radiosity.size(); ++e) radiosity[e] = solution.displayRadiosity(e);
  return radiosity;
}

}  // namespace

SourceTree::SourceTree(const Solution &solution) : SourceTree(solution.mesh, displayRadiosities(solution)) {}

SourceTree::SourceTree(const RadiosityMesh &mesh, const std::vector<Bands> &radiosity) {
  const size_t n = mesh.elements.size();
  std::vector<double> power(n, 0.0);
  std::vector<Vec3> lo(n), hi(n);
  std::vector<uint32_t> sources;
  for (uint32_t e = 0; e < n; ++e) {
    power[e] = mesh.elements[e].area * radiosity[e].average();
    if (!(power[e] > 0)) continue;
    const std::vector<Vec3> polygon = mesh.polygon(e);
    lo[e] = hi[e] = polygon[0];
    for (const Vec3 &p : polygon) lo[e] = lower(lo[e], p), hi[e] = upper(hi[e], p);
    sources.push_back(e);
  }
  if (sources.empty()) return;
  nodes_.reserve(2 * sources.size());
  root_ = build(sources, 0, sources.size(), mesh, power, lo, hi);
  order_ = std::move(sources);  // build left them in tree order
  powerThrough_.resize(order_.size());
  double sum = 0;
  for (size_t k = 0; k < order_.size(); ++k) powerThrough_[k] = sum += power[order_[k]];
}

uint32_t SourceTree::build(std::vector<uint32_t> &elements, size_t begin, size_t end, const RadiosityMesh &mesh,
                           const std::vector<double> &power, const std::vector<Vec3> &lo, const std::vector<Vec3> &hi) {
  Node node;
  node.lo = lo[elements[begin]], node.hi = hi[elements[begin]];
  Vec3 areaNormal{}, centreLo = mesh.elements[elements[begin]].centre, centreHi = centreLo;
  Vec3 normalLo = mesh.normalOf(elements[begin]), normalHi = normalLo;
  for (size_t k = begin; k < end; ++k) {
    const uint32_t e = elements[k];
    node.lo = lower(node.lo, lo[e]), node.hi = upper(node.hi, hi[e]);
    node.power += power[e];
    node.centre += mesh.elements[e].centre * power[e];
    areaNormal += mesh.normalOf(e) * mesh.elements[e].area;
    centreLo = lower(centreLo, mesh.elements[e].centre), centreHi = upper(centreHi, mesh.elements[e].centre);
    normalLo = lower(normalLo, mesh.normalOf(e)), normalHi = upper(normalHi, mesh.normalOf(e));
  }
  node.centre = node.centre / node.power;
  const double axisLength = length(areaNormal);
  node.axis = axisLength > 1e-9 ? areaNormal / axisLength : Vec3{0, 0, 1};
  node.cosSpread = axisLength > 1e-9 ? 1.0 : -1.0;
  if (axisLength > 1e-9)
    for (size_t k = begin; k < end; ++k)
      node.cosSpread = std::min(node.cosSpread, dot(mesh.normalOf(elements[k]), node.axis));
  node.cosSpread = std::clamp(node.cosSpread, -1.0, 1.0);
  node.sinSpread = std::sqrt(1 - node.cosSpread * node.cosSpread);
  node.sphereCentre = (node.lo + node.hi) * 0.5;
  node.radius = 0.5 * length(node.hi - node.lo);
  node.first = uint32_t(begin), node.count = uint32_t(end - begin);
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.push_back(node);
  if (end - begin == 1) {
    nodes_[index].leaf = true;
    nodes_[index].left = nodes_[index].right = elements[begin];
    return index;
  }
  // Split at the median of the widest of six extents: the centres' along x,
  // y, z and the normals' components scaled by half the box's diagonal, so
  // that the walls of a room part by their orientation before their place
  // (a node of one orientation has a tight cone, and its bound a cosine).
  const Vec3 centreExtent = centreHi - centreLo;
  const Vec3 normalExtent = (normalHi - normalLo) * (0.5 * length(node.hi - node.lo));
  const double extents[6] = {centreExtent.x, centreExtent.y, centreExtent.z,
                             normalExtent.x, normalExtent.y, normalExtent.z};
  const int dimension = int(std::max_element(extents, extents + 6) - extents);
  auto key = [&](uint32_t e) {
    const Vec3 &v = dimension < 3 ? mesh.elements[e].centre : mesh.normalOf(e);
    const int axis = dimension % 3;
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
  };
  const size_t middle = begin + (end - begin) / 2;
  std::nth_element(elements.begin() + std::ptrdiff_t(begin), elements.begin() + std::ptrdiff_t(middle),
                   elements.begin() + std::ptrdiff_t(end), [&](uint32_t a, uint32_t b) {
                     const double ka = key(a), kb = key(b);
                     return ka < kb || (ka == kb && a < b);  // the same tree on every run
                   });
  const uint32_t left = build(elements, begin, middle, mesh, power, lo, hi);
  const uint32_t right = build(elements, middle, end, mesh, power, lo, hi);
  nodes_[index].left = left, nodes_[index].right = right;
  return index;
}

// The bounds use the node's bounding sphere, seen from x at distance D under
// the half-angle α (sin α = r / D): every direction into it is within α of
// the direction to its centre, and every direction from it to x within α of
// the reverse. The angles are subtracted with the cosines' and sines'
// difference formulas, without a trigonometric call.
double SourceTree::cosineBound(const Node &node, const Vec3 &x, const Vec3 &n) const {
  const Vec3 v = node.sphereCentre - x;
  const double d2 = dot(v, v);
  if (d2 <= node.radius * node.radius) return 1;
  const double d = std::sqrt(d2), sinAlpha = node.radius / d, cosAlpha = std::sqrt(1 - sinAlpha * sinAlpha);
  // θ: from x's normal to the centre, less α.
  const double cosTheta = dot(n, v) / d, sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  double cosReceiver = 1;
  if (cosTheta < cosAlpha) {  // θ > α
    cosReceiver = cosTheta * cosAlpha + sinTheta * sinAlpha;
    if (cosReceiver <= 0) return 0;
  }
  if (node.cosSpread <= -1) return cosReceiver;
  // φ: from the cone's axis to the direction from the centre to x, less α, less the cone's half-angle.
  const double cosPhi = -dot(node.axis, v) / d, sinPhi = std::sqrt(std::max(0.0, 1 - cosPhi * cosPhi));
  if (cosPhi >= cosAlpha) return cosReceiver;                       // φ ≤ α
  const double cosReduced = cosPhi * cosAlpha + sinPhi * sinAlpha;  // cos(φ − α)
  const double sinReduced = sinPhi * cosAlpha - cosPhi * sinAlpha;  // sin(φ − α) > 0
  if (cosReduced >= node.cosSpread) return cosReceiver;             // φ − α ≤ the half-angle
  const double cosSource = cosReduced * node.cosSpread + sinReduced * node.sinSpread;
  return cosSource <= 0 ? 0 : cosReceiver * cosSource;
}

double SourceTree::bound(const Node &node, const Vec3 &x, const Vec3 &n) const {
  const Vec3 v = node.sphereCentre - x;
  const double d = std::sqrt(dot(v, v)) - node.radius;
  if (d <= 0) return std::numeric_limits<double>::infinity();
  return node.power * cosineBound(node, x, n) / (kPi * d * d);
}

double SourceTree::estimate(const Node &node, const Vec3 &x, const Vec3 &n) const {
  const Vec3 v = node.centre - x;
  const double r2 = std::max(dot(v, v), 1e-18), r = std::sqrt(r2);
  const double cosReceiver = std::max(0.0, dot(n, v) / r);
  const double cosSource = node.cosSpread > 0.99 ? std::max(0.0, -dot(node.axis, v) / r) : 0.5;
  return node.power * cosReceiver * cosSource / (kPi * r2);
}

void SourceTree::chooseCut(const Vec3 &x, const Vec3 &n, double relativeError, int maxNodes, std::vector<CutNode> &cut,
                           Work *work) const {
  cut.clear();
  if (nodes_.empty()) return;
  struct Open {
    double bound, estimate;
    uint32_t node;
    bool operator<(const Open &o) const { return bound < o.bound; }
  };
  thread_local std::vector<Open> open;
  open.clear();
  double total = 0;  // the unoccluded estimate of the cut, the scale of its errors
  auto add = [&](uint32_t index) {
    const Node &node = nodes_[index];
    if (node.leaf) {
      if (bound(node, x, n) > 0) cut.push_back({index, true}), total += estimate(node, x, n);
      return;
    }
    const double b = bound(node, x, n);
    if (b <= 0) return;  // every element faces away from x, or x from it: no light
    const double e = std::min(estimate(node, x, n), b);
    open.push_back({b, e, index});
    std::push_heap(open.begin(), open.end());
    total += e;
  };
  add(root_);
  while (!open.empty()) {
    const Open &largest = open.front();
    if (relativeError > 0 && (largest.bound <= relativeError * total || int(cut.size() + open.size()) >= maxNodes))
      break;
    const Open split = largest;
    std::pop_heap(open.begin(), open.end());
    open.pop_back();
    total -= split.estimate;
    if (work) ++work->splits;
    add(nodes_[split.node].left);
    add(nodes_[split.node].right);
  }
  for (const Open &o : open) cut.push_back({o.node, false});
}

uint32_t SourceTree::drawElement(uint32_t index, const Vec3 &x, const Vec3 &n, double u, double &probability,
                                 Work *work) const {
  probability = 1;
  while (!nodes_[index].leaf) {
    if (work) ++work->levels;
    const Node &node = nodes_[index];
    // Far (every element within about ±25 % of the centre's distance) and of
    // one orientation (normals within 25°): by power, at once.
    const Vec3 v = node.sphereCentre - x;
    if (node.cosSpread > 0.9 && dot(v, v) > 16 * node.radius * node.radius) return drawByPower(node, u, probability);
    double left = importance(nodes_[node.left], x, n), right = importance(nodes_[node.right], x, n);
    if (!(left + right > 0) || !std::isfinite(left + right))  // nothing known, or x inside both: by power
      left = nodes_[node.left].power, right = nodes_[node.right].power;
    const double pLeft = left / (left + right);
    if (u < pLeft) {
      u = u / pLeft;
      index = node.left;
      probability *= pLeft;
    } else {
      u = std::min((u - pLeft) / (1 - pLeft), std::nextafter(1.0, 0.0));
      index = node.right;
      probability *= 1 - pLeft;
    }
  }
  return nodes_[index].left;
}

uint32_t SourceTree::drawByPower(const Node &node, double u, double &probability) const {
  const double before = node.first > 0 ? powerThrough_[node.first - 1] : 0.0;
  const double total = powerThrough_[node.first + node.count - 1] - before;
  const auto begin = powerThrough_.begin() + node.first, end = begin + node.count;
  // The first element whose interval [through(k − 1), through(k)) holds the target.
  auto at = std::upper_bound(begin, end, before + u * total);
  if (at == end) --at;  // u·total rounded up to the very end
  // Its chance is its interval's length over the node's, from the same sums the search used.
  while (at != begin && *at == *(at - 1)) --at;  // never an empty interval (only after that rounding)
  const double lower = at == begin ? before : *(at - 1);
  probability *= (*at - lower) / total;
  return order_[size_t(at - powerThrough_.begin())];
}

double SourceTree::importance(const Node &node, const Vec3 &x, const Vec3 &n) const {
  const Vec3 toCentre = node.centre - x;
  const double d2 = std::max(dot(toCentre, toCentre), node.radius * node.radius);
  return node.power * cosineBound(node, x, n) / d2;
}

}  // namespace radiant
