#include "export/lightmap_atlas.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <unordered_map>

#include "util/error.h"

namespace radiant {

namespace {

struct Point2 {
  double x = 0, y = 0;
};

double cross2(const Point2 &o, const Point2 &a, const Point2 &b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

/// Andrew's monotone chain: the convex hull, counter-clockwise, no repeated point.
std::vector<Point2> convexHull(std::vector<Point2> points) {
  std::sort(points.begin(), points.end(),
            [](const Point2 &a, const Point2 &b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (points.size() < 3) return points;
  std::vector<Point2> hull(2 * points.size());
  size_t k = 0;
  for (const Point2 &p : points) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// A vertex position's identity: triangles sharing an edge share its two
/// corners exactly (they come from the scene's shared vertices).
struct PositionHash {
  size_t operator()(const Vec3 &p) const {
    uint64_t h = 1469598103934665603ull;
    for (double c : {p.x, p.y, p.z}) {
      uint64_t bits;
      c = c == 0 ? 0.0 : c;  // −0 and +0 are one position
      std::memcpy(&bits, &c, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return size_t(h);
  }
};
struct PositionEqual {
  bool operator()(const Vec3 &a, const Vec3 &b) const { return a.x == b.x && a.y == b.y && a.z == b.z; }
};

/// The triangles sharing each triangle's edges (edge k joins corners k and k + 1).
std::vector<std::array<std::vector<uint32_t>, 3>> edgeNeighbours(std::span<const LightmapTriangle> triangles) {
  std::unordered_map<Vec3, uint32_t, PositionHash, PositionEqual> vertexId;
  auto id = [&](const Vec3 &p) { return vertexId.emplace(p, uint32_t(vertexId.size())).first->second; };
  std::unordered_map<uint64_t, std::vector<uint32_t>> trianglesOfEdge;
  std::vector<std::array<uint64_t, 3>> edgeKeys(triangles.size());
  for (uint32_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = id(triangles[t].corners[k]), b = id(triangles[t].corners[(k + 1) % 3]);
      const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
      edgeKeys[t][size_t(k)] = key;
      trianglesOfEdge[key].push_back(t);
    }
  std::vector<std::array<std::vector<uint32_t>, 3>> neighbours(triangles.size());
  for (uint32_t t = 0; t < triangles.size(); ++t)
    for (size_t k = 0; k < 3; ++k)
      for (uint32_t other : trianglesOfEdge[edgeKeys[t][k]])
        if (other != t) neighbours[t][k].push_back(other);
  return neighbours;
}

/// A chart flattened and turned to its smallest bounding rectangle, in metres.
struct FlatChart {
  std::vector<uint32_t> triangles;
  std::vector<Point2> corners;  ///< 3 per triangle, in the rectangle's frame: [0, width] × [0, height]
  double width = 0, height = 0;
};

FlatChart flattenChart(std::span<const LightmapTriangle> triangles, std::vector<uint32_t> members,
                       const std::vector<Vec3> &normals, const std::vector<double> &areas) {
  Vec3 meanNormal;
  for (uint32_t t : members) meanNormal += normals[t] * areas[t];
  meanNormal = normalize(meanNormal);
  // Any two axes across the mean normal.
  const Vec3 helper = std::abs(meanNormal.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 axisU = normalize(cross(helper, meanNormal)), axisV = cross(meanNormal, axisU);
  FlatChart chart;
  chart.triangles = std::move(members);
  for (uint32_t t : chart.triangles)
    for (const Vec3 &p : triangles[t].corners) chart.corners.push_back({dot(p, axisU), dot(p, axisV)});

  // The smallest rectangle has a side along one of the hull's edges.
  const std::vector<Point2> hull = convexHull(chart.corners);
  double bestArea = INFINITY, bestCos = 1, bestSin = 0;
  for (size_t i = 0; i < hull.size(); ++i) {
    const Point2 &a = hull[i], &b = hull[(i + 1) % hull.size()];
    const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
    if (!(len > 0)) continue;
    const double c = dx / len, s = dy / len;
    double minX = INFINITY, maxX = -INFINITY, minY = INFINITY, maxY = -INFINITY;
    for (const Point2 &p : hull) {
      const double x = c * p.x + s * p.y, y = -s * p.x + c * p.y;
      minX = std::min(minX, x), maxX = std::max(maxX, x), minY = std::min(minY, y), maxY = std::max(maxY, y);
    }
    const double area = (maxX - minX) * (maxY - minY);
    if (area < bestArea) bestArea = area, bestCos = c, bestSin = s;
  }
  double minX = INFINITY, maxX = -INFINITY, minY = INFINITY, maxY = -INFINITY;
  for (Point2 &p : chart.corners) {
    p = {bestCos * p.x + bestSin * p.y, -bestSin * p.x + bestCos * p.y};
    minX = std::min(minX, p.x), maxX = std::max(maxX, p.x), minY = std::min(minY, p.y), maxY = std::max(maxY, p.y);
  }
  // Wider than tall, so that shelves (rows) fill with fewer gaps.
  const bool turn = maxY - minY > maxX - minX;
  for (Point2 &p : chart.corners) p = turn ? Point2{p.y - minY, maxX - p.x} : Point2{p.x - minX, p.y - minY};
  chart.width = turn ? maxY - minY : maxX - minX;
  chart.height = turn ? maxX - minX : maxY - minY;
  return chart;
}

/// True when two triangles of the flattened chart overlap: interiors that
/// intersect, by the separating axis theorem on their six edge normals (two
/// convex polygons with disjoint interiors are separated along one of them).
/// Triangles that only touch (a shared edge or corner) do not overlap. The
/// candidates are the pairs that share a cell of a grid over the chart.
bool chartFolds(const FlatChart &chart) {
  const size_t n = chart.triangles.size();
  if (n < 2) return false;
  const double size = std::max(chart.width, chart.height);
  const double tolerance = 1e-9 * size;
  const int cells = std::clamp(int(std::sqrt(double(n))), 1, 1024);
  const double cellWidth = std::max(chart.width, tolerance) / cells,
               cellHeight = std::max(chart.height, tolerance) / cells;
  std::vector<std::vector<uint32_t>> grid(size_t(cells) * size_t(cells));
  auto cell = [&](double v, double step) { return std::clamp(int(v / step), 0, cells - 1); };
  for (uint32_t i = 0; i < n; ++i) {
    const Point2 *p = &chart.corners[3 * i];
    const double x0 = std::min({p[0].x, p[1].x, p[2].x}), x1 = std::max({p[0].x, p[1].x, p[2].x});
    const double y0 = std::min({p[0].y, p[1].y, p[2].y}), y1 = std::max({p[0].y, p[1].y, p[2].y});
    for (int y = cell(y0, cellHeight); y <= cell(y1, cellHeight); ++y)
      for (int x = cell(x0, cellWidth); x <= cell(x1, cellWidth); ++x)
        grid[size_t(y) * size_t(cells) + size_t(x)].push_back(i);
  }
  auto separated = [&](const Point2 *a, const Point2 *b) {
    for (const Point2 *edges : {a, b})
      for (int k = 0; k < 3; ++k) {
        const Point2 &e0 = edges[k], &e1 = edges[(k + 1) % 3];
        const double nx = e0.y - e1.y, ny = e1.x - e0.x, length = std::hypot(nx, ny);
        if (!(length > 0)) continue;
        double aMin = INFINITY, aMax = -INFINITY, bMin = INFINITY, bMax = -INFINITY;
        for (int v = 0; v < 3; ++v) {
          const double pa = (a[v].x * nx + a[v].y * ny) / length, pb = (b[v].x * nx + b[v].y * ny) / length;
          aMin = std::min(aMin, pa), aMax = std::max(aMax, pa), bMin = std::min(bMin, pb), bMax = std::max(bMax, pb);
        }
        if (aMax <= bMin + tolerance || bMax <= aMin + tolerance) return true;
      }
    return false;
  };
  for (const std::vector<uint32_t> &inCell : grid)
    for (size_t i = 0; i < inCell.size(); ++i)
      for (size_t j = i + 1; j < inCell.size(); ++j)
        if (!separated(&chart.corners[3 * inCell[i]], &chart.corners[3 * inCell[j]])) return true;
  return false;
}

/// A chart's rectangle at a texel size: the chart spans [0.5, 0.5 + extent/texel]
/// texels from the rectangle's corner, so its edges lie at least half a texel inside.
int texelsAcross(double metres, double texelSize) {
  return std::max(1, int(std::ceil(metres / texelSize + 1.0)));
}

struct Placement {
  std::vector<std::array<int, 2>> corner;  ///< per chart
  int width = 0, height = 0;
};

/// Shelf packing (tallest first) into rows `width` texels wide. Height: as many rows as it takes.
Placement packShelves(const std::vector<FlatChart> &charts, const std::vector<uint32_t> &tallestFirst, double texelSize,
                      int width, int padding) {
  Placement placement;
  placement.corner.resize(charts.size());
  placement.width = width;
  int x = padding, y = padding, shelfHeight = 0;
  for (uint32_t c : tallestFirst) {
    const int w = texelsAcross(charts[c].width, texelSize), h = texelsAcross(charts[c].height, texelSize);
    if (x + w + padding > width && x > padding) {
      y += shelfHeight + padding;
      x = padding;
      shelfHeight = 0;
    }
    placement.corner[c] = {x, y};
    x += w + padding;
    shelfHeight = std::max(shelfHeight, h);
  }
  placement.height = y + shelfHeight + padding;
  return placement;
}

int roundUpTo4(double texels) {
  return int(std::ceil(texels / 4.0)) * 4;
}

}  // namespace

LightmapAtlas buildLightmapAtlas(std::span<const LightmapTriangle> triangles, const AtlasOptions &options) {
  if (options.padding < 0 || options.texelSize < 0 || (options.texelSize == 0 && options.size < 8))
    throw InputError(InputLocation{"lightmap"}, "the texel size must be positive, or the lightmap at least 8 texels");
  LightmapAtlas atlas;
  atlas.chartOfTriangle.assign(triangles.size(), -1);
  std::vector<Vec3> normals(triangles.size());
  std::vector<double> areas(triangles.size());
  double largestSide = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Vec3 *p = triangles[t].corners;
    const Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
    areas[t] = 0.5 * length(n);
    normals[t] = areas[t] > 0 ? n / (2 * areas[t]) : Vec3();
    for (int k = 0; k < 3; ++k) largestSide = std::max(largestSide, length(p[(k + 1) % 3] - p[k]));
  }
  // A triangle thinner than round-off has no normal to chart by, and no texel to fill.
  const double degenerateArea = 1e-12 * largestSide * largestSide;

  // Charts, grown from the largest triangles outwards across shared edges (breadth first).
  const auto neighbours = edgeNeighbours(triangles);
  std::vector<uint32_t> bySize(triangles.size());
  std::iota(bySize.begin(), bySize.end(), 0u);
  std::stable_sort(bySize.begin(), bySize.end(), [&](uint32_t a, uint32_t b) { return areas[a] > areas[b]; });
  std::vector<FlatChart> charts;
  std::vector<uint32_t> members;
  for (uint32_t seed : bySize) {
    if (atlas.chartOfTriangle[seed] >= 0 || !(areas[seed] > degenerateArea)) continue;
    const int32_t chart = int32_t(charts.size());
    // A chart whose projection folds over itself (a ramp winding round, within the cone) is grown
    // again with half the angle, until it does not: one triangle never folds. Its released
    // triangles come after the seed in size order, so later charts take them.
    for (double angle = options.maxChartAngleDegrees;; angle /= 2) {
      const double cosMax = std::cos(angle * kPi / 180);
      members.assign(1, seed);
      atlas.chartOfTriangle[seed] = chart;
      for (size_t next = 0; next < members.size(); ++next)
        for (const auto &across : neighbours[members[next]])
          for (uint32_t t : across)
            if (atlas.chartOfTriangle[t] < 0 && areas[t] > degenerateArea && dot(normals[t], normals[seed]) >= cosMax) {
              atlas.chartOfTriangle[t] = chart;
              members.push_back(t);
            }
      FlatChart flat = flattenChart(triangles, members, normals, areas);
      if (members.size() == 1 || !chartFolds(flat)) {
        charts.push_back(std::move(flat));
        break;
      }
      for (uint32_t t : members) atlas.chartOfTriangle[t] = -1;
    }
  }

  std::vector<uint32_t> tallestFirst(charts.size());
  std::iota(tallestFirst.begin(), tallestFirst.end(), 0u);
  std::stable_sort(tallestFirst.begin(), tallestFirst.end(), [&](uint32_t a, uint32_t b) {
    return charts[a].height > charts[b].height ||
           (charts[a].height == charts[b].height && charts[a].width > charts[b].width);
  });
  const int padding = options.padding;
  auto widest = [&](double texelSize) {
    int w = 0;
    for (const FlatChart &c : charts) w = std::max(w, texelsAcross(c.width, texelSize));
    return w + 2 * padding;
  };
  double totalArea = 0;
  for (const FlatChart &c : charts) totalArea += c.width * c.height;
  Placement placement;
  if (charts.empty()) {
    atlas.texelSize = options.texelSize > 0 ? options.texelSize : 1;
    placement.width = placement.height = 4;
  } else if (options.texelSize > 0) {
    // A square-ish atlas: rows as wide as the charts' padded area's square root, and the widest chart.
    atlas.texelSize = options.texelSize;
    double paddedArea = 0;
    for (const FlatChart &c : charts)
      paddedArea += double(texelsAcross(c.width, atlas.texelSize) + padding) *
                    double(texelsAcross(c.height, atlas.texelSize) + padding);
    const double side = std::sqrt(paddedArea * 1.1) + padding;
    auto tooSmall = [&] {
      return InputError(InputLocation{"--texel-size"},
                        "a texel of " + std::to_string(atlas.texelSize * 1e3) + " mm needs a lightmap over " +
                            std::to_string(kMaxLightmapSide) + " texels a side: give a larger texel size");
    };
    if (std::max(side, double(widest(atlas.texelSize))) > kMaxLightmapSide) throw tooSmall();
    placement = packShelves(charts, tallestFirst, atlas.texelSize, std::max(roundUpTo4(side), widest(atlas.texelSize)),
                            padding);
    placement.width = roundUpTo4(placement.width);
    placement.height = roundUpTo4(placement.height);
    if (std::max(placement.width, placement.height) > kMaxLightmapSide) throw tooSmall();
  } else {
    // The smallest texel (bisection on its logarithm) whose packing fits size × size.
    const int size = options.size;
    auto fits = [&](double texelSize) {
      return widest(texelSize) <= size && packShelves(charts, tallestFirst, texelSize, size, padding).height <= size;
    };
    double small = std::sqrt(totalArea / (double(size) * size)), large = small;
    for (int i = 0; i < 60 && !fits(large); ++i) large *= 2;
    if (!fits(large))
      throw InputError(InputLocation{"--lightmap-size"},
                       std::to_string(charts.size()) + " charts with " + std::to_string(padding) +
                           " texels of padding do not fit a lightmap of " + std::to_string(size) + " texels a side");
    for (int i = 0; i < 40; ++i) {
      const double middle = std::sqrt(small * large);
      (fits(middle) ? large : small) = middle;
    }
    atlas.texelSize = large;
    placement = packShelves(charts, tallestFirst, large, size, padding);
    placement.width = placement.height = size;
  }
  atlas.width = placement.width;
  atlas.height = placement.height;

  atlas.texelCoordinates.assign(6 * triangles.size(), 0.0);
  atlas.charts.reserve(charts.size());
  for (size_t c = 0; c < charts.size(); ++c) {
    const FlatChart &flat = charts[c];
    LightmapChart chart;
    chart.triangles = flat.triangles;
    chart.x = placement.corner[c][0];
    chart.y = placement.corner[c][1];
    chart.width = texelsAcross(flat.width, atlas.texelSize);
    chart.height = texelsAcross(flat.height, atlas.texelSize);
    for (size_t i = 0; i < flat.triangles.size(); ++i)
      for (size_t k = 0; k < 3; ++k) {
        const Point2 &p = flat.corners[3 * i + k];
        double *uv = &atlas.texelCoordinates[6 * flat.triangles[i] + 2 * k];
        uv[0] = chart.x + 0.5 + p.x / atlas.texelSize;
        uv[1] = chart.y + 0.5 + p.y / atlas.texelSize;
      }
    atlas.charts.push_back(std::move(chart));
  }
  return atlas;
}

}  // namespace radiant
