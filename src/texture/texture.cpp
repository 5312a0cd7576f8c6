// Texture lookups for surface detail (Cohen & Wallace §9.4, eq. 9.11;
// Chen & Wu, SIGGRAPH 1990).
//
// What it computes, per band, in linear units (reflectance, or height for a
// bump map):
//   bilinear  the finest level, interpolated between texel centres;
//   filtered  trilinear mip-mapping (Williams 1983): bilinear in the two
//             levels whose texels bracket the pixel's footprint, blended by
//             log2 of the footprint;
//   average   the exact integral of the bilinear reconstruction over a convex
//             polygon divided by its area: the element's area-averaged
//             reflectance ρ̄ that the radiosity solution uses (C&W eq. 9.11,
//             B(x) = B(ρ̄)·ρ(x)/ρ̄ at render time);
//   gradient  ∂h/∂u, ∂h/∂v of the bilinear reconstruction, for bump maps.
//
// The pyramid is built with an area-weighted box filter: level L+1 has
// ⌈w/2⌉ × ⌈h/2⌉ texels and each of them is the exact mean of level L over the
// same square of texture space. For odd sizes a coarse texel therefore takes
// fractional parts of three fine texels, so every level keeps the mean (to
// float rounding) and coarse levels are exact local averages, which is what
// lets average() switch to them for large polygons.
#include "texture/texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace radiant {

namespace {

using Point = std::array<double, 2>;
using Polygon = std::vector<Point>;

/// average() integrates at the finest level on which the polygon meets at
/// most this many cells of the bilinear reconstruction; see Texture::average().
constexpr double kMaxAverageCells = 4096;
/// Below this area in finest-level texels² a polygon counts as degenerate:
/// its clipped pieces' moments would be mostly rounding error.
constexpr double kNegligibleTexelArea = 1e-12;

/// Read-only access to one pyramid level with the texture's wrap mode.
struct LevelView {
  int width = 0, height = 0;
  const float *texels = nullptr;
  TextureWrap wrap = TextureWrap::Repeat;
};

long long wrapIndex(long long i, int n, TextureWrap wrap) {
  if (wrap == TextureWrap::Clamp) return std::clamp<long long>(i, 0, n - 1);
  long long r = i % n;
  return r < 0 ? r + n : r;
}

Bands fetch(const LevelView &level, long long i, long long j) {
  const long long x = wrapIndex(i, level.width, level.wrap), y = wrapIndex(j, level.height, level.wrap);
  const float *t = level.texels + (y * level.width + x) * 3;
  return {t[0], t[1], t[2]};
}

/// Texture coordinate into [0, 1]: the fractional part for Repeat (periodic,
/// and keeps huge coordinates from overflowing texel indices), clamped for
/// Clamp. A non-finite coordinate reads as 0 rather than poisoning an image.
double wrapCoordinate(double t, TextureWrap wrap) {
  if (!std::isfinite(t)) return 0;
  return wrap == TextureWrap::Repeat ? t - std::floor(t) : std::clamp(t, 0.0, 1.0);
}

/// Where (u, v) falls among the texel centres: the cell whose corners are the
/// centres (i, j), (i+1, j), (i, j+1), (i+1, j+1) (j counts rows down from the
/// top, so v up is j down) and the fractions (fx, fy) ∈ [0, 1) across it.
struct Cell {
  long long i = 0, j = 0;
  double fx = 0, fy = 0;
};

Cell locate(const LevelView &level, double u, double v) {
  const double x = wrapCoordinate(u, level.wrap) * level.width - 0.5;
  const double y = (1 - wrapCoordinate(v, level.wrap)) * level.height - 0.5;
  const double i = std::floor(x), j = std::floor(y);
  return {static_cast<long long>(i), static_cast<long long>(j), x - i, y - j};
}

Bands interpolate(const LevelView &level, const Cell &c) {
  return (1 - c.fy) * ((1 - c.fx) * fetch(level, c.i, c.j) + c.fx * fetch(level, c.i + 1, c.j)) +
         c.fy * ((1 - c.fx) * fetch(level, c.i, c.j + 1) + c.fx * fetch(level, c.i + 1, c.j + 1));
}

// ---- Pyramid ----

struct Tap {
  int fine = 0;
  double weight = 0;
};

/// The area-weighted box filter from n texels to m = ⌈n/2⌉ along one axis:
/// coarse texel c covers fine texels [c·s, (c+1)·s), s = n/m ∈ [1, 2], and
/// takes each fine texel with the fraction of it that lies inside, over s.
/// Each fine texel's weights sum to 1/s, so the mean is preserved exactly.
std::vector<std::vector<Tap>> halvingTaps(int n) {
  const int m = (n + 1) / 2;
  const double s = double(n) / m;
  std::vector<std::vector<Tap>> taps(m);
  for (int c = 0; c < m; ++c) {
    const double lo = c * s, hi = (c + 1) * s;
    for (int f = int(std::floor(lo)); f < n && f < hi; ++f) {
      const double overlap = std::min<double>(f + 1, hi) - std::max<double>(f, lo);
      if (overlap > 0) taps[c].push_back({f, overlap / s});
    }
  }
  return taps;
}

/// The next pyramid level: the box filter along rows, then along columns,
/// accumulated in double so that the only rounding is the final float store.
/// (A template only because Texture::Level is private.)
template <typename Level>
Level halve(const Level &fine) {
  const int w = fine.width, h = fine.height, w2 = (w + 1) / 2, h2 = (h + 1) / 2;
  const auto tapsX = halvingTaps(w), tapsY = halvingTaps(h);
  std::vector<double> rows(size_t(h) * w2 * 3, 0.0);
  for (int j = 0; j < h; ++j)
    for (int c = 0; c < w2; ++c)
      for (const Tap &t : tapsX[c])
        for (int b = 0; b < 3; ++b)
          rows[(size_t(j) * w2 + c) * 3 + b] += t.weight * fine.texels[(size_t(j) * w + t.fine) * 3 + b];
  Level coarse{w2, h2, std::vector<float>(size_t(w2) * h2 * 3)};
  std::vector<double> sum(size_t(w2) * 3);
  for (int r = 0; r < h2; ++r) {
    std::fill(sum.begin(), sum.end(), 0.0);
    for (const Tap &t : tapsY[r])
      for (size_t k = 0; k < sum.size(); ++k) sum[k] += t.weight * rows[size_t(t.fine) * w2 * 3 + k];
    std::copy(sum.begin(), sum.end(), coarse.texels.begin() + ptrdiff_t(size_t(r) * w2 * 3));
  }
  return coarse;
}

// ---- Exact integral of the bilinear reconstruction over a polygon ----

/// Sutherland–Hodgman against one axis-aligned half-plane: keeps the part of
/// `in` where p[axis] ≥ bound (keepAbove) or ≤ bound. Orientation is kept.
void clipHalfPlane(const Polygon &in, int axis, double bound, bool keepAbove, Polygon &out) {
  out.clear();
  auto inside = [&](const Point &p) { return keepAbove ? p[axis] >= bound : p[axis] <= bound; };
  for (size_t k = 0; k < in.size(); ++k) {
    const Point &a = in[k], &b = in[(k + 1) % in.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const double t = (bound - a[axis]) / (b[axis] - a[axis]);
      Point p{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
      p[axis] = bound;  // exactly on the line, so neighbouring cells share the edge
      out.push_back(p);
    }
  }
}

/// Keeps the part of `polygon` with lo ≤ p[axis] ≤ lo + 1.
void clipSlab(const Polygon &polygon, int axis, double lo, Polygon &scratch, Polygon &out) {
  clipHalfPlane(polygon, axis, lo, true, scratch);
  clipHalfPlane(scratch, axis, lo + 1, false, out);
}

/// ∫1, ∫x, ∫y, ∫xy over a polygon by Green's theorem (signed by orientation).
struct Moments {
  double area = 0, x = 0, y = 0, xy = 0;
};

Moments moments(const Polygon &p, double originX, double originY) {
  Moments m;
  for (size_t k = 0; k < p.size(); ++k) {
    const double x0 = p[k][0] - originX, y0 = p[k][1] - originY;
    const double x1 = p[(k + 1) % p.size()][0] - originX, y1 = p[(k + 1) % p.size()][1] - originY;
    const double cross = x0 * y1 - x1 * y0;
    m.area += cross;
    m.x += (x0 + x1) * cross;
    m.y += (y0 + y1) * cross;
    m.xy += (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0) * cross;
  }
  m.area /= 2;
  m.x /= 6;
  m.y /= 6;
  m.xy /= 24;
  return m;
}

/// ∫ over the piece of the cell (i, j) of the bilinear reconstruction: with
/// local coordinates (x, y) ∈ [0, 1]² across the cell the interpolant is
/// t00(1−x)(1−y) + t10·x(1−y) + t01(1−x)y + t11·xy, so its integral is a
/// combination of the piece's moments.
Bands integrateCell(const LevelView &level, long long i, long long j, const Moments &m) {
  return (m.area - m.x - m.y + m.xy) * fetch(level, i, j) + (m.x - m.xy) * fetch(level, i + 1, j) +
         (m.y - m.xy) * fetch(level, i, j + 1) + m.xy * fetch(level, i + 1, j + 1);
}

/// The mean of the bilinear reconstruction of `level` over `uv`: the polygon
/// is cut into the cells between texel centres (column strips, then rows) and
/// each piece is integrated exactly from its moments. Dividing by the pieces'
/// own summed area makes a constant texture come out as exactly that constant.
Bands integrateBilinear(const LevelView &level, const Polygon &uv) {
  Polygon texels, strip, piece, scratch;
  for (const Point &p : uv) texels.push_back({p[0] * level.width - 0.5, (1 - p[1]) * level.height - 0.5});
  double xMin = texels[0][0], xMax = xMin;
  for (const Point &p : texels) xMin = std::min(xMin, p[0]), xMax = std::max(xMax, p[0]);
  Bands integral;
  double area = 0;
  for (long long i = static_cast<long long>(std::floor(xMin)); i < std::ceil(xMax); ++i) {
    clipSlab(texels, 0, double(i), scratch, strip);
    if (strip.size() < 3) continue;
    double yMin = strip[0][1], yMax = yMin;
    for (const Point &p : strip) yMin = std::min(yMin, p[1]), yMax = std::max(yMax, p[1]);
    for (long long j = static_cast<long long>(std::floor(yMin)); j < std::ceil(yMax); ++j) {
      clipSlab(strip, 1, double(j), scratch, piece);
      if (piece.size() < 3) continue;
      const Moments m = moments(piece, double(i), double(j));
      integral += integrateCell(level, i, j, m);
      area += m.area;
    }
  }
  return area != 0 ? integral / area : Bands();
}

/// An upper bound on the cells of a level with `width` × `height` texels that
/// a convex polygon of area `areaUv` and bounding box `spanU` × `spanV` meets:
/// the cells wholly inside (≤ its area) plus those its boundary crosses (a
/// convex boundary crosses each grid line at most twice).
double cellsMet(int width, int height, double areaUv, double spanU, double spanV) {
  return areaUv * width * height + 2 * (spanU * width + spanV * height) + 5;
}

double signedArea(const Polygon &p) {
  return moments(p, p[0][0], p[0][1]).area;
}

/// Texels as the pyramid stores them, 3 floats each: float halves the memory
/// of a 4096² texture and is far finer than any reflectance is known.
std::vector<float> toFloats(int width, int height, const std::vector<Bands> &texels) {
  if (width < 1 || height < 1 || texels.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("Texture: need width, height ≥ 1 and width × height texels");
  std::vector<float> floats(texels.size() * 3);
  for (size_t k = 0; k < texels.size(); ++k)
    for (int b = 0; b < 3; ++b) floats[k * 3 + b] = float(texels[k][b]);
  return floats;
}

}  // namespace

// ---- Construction ----

Texture::Texture(int width, int height, std::vector<Bands> texels, TextureWrap wrap)
    : Texture(Level{width, height, toFloats(width, height, texels)}, wrap) {}

Texture::Texture(Level finest, TextureWrap wrap) : wrap_(wrap) {
  levels_.push_back(std::move(finest));
  while (levels_.back().width > 1 || levels_.back().height > 1) levels_.push_back(halve(levels_.back()));
  const std::vector<float> &t = levels_[0].texels;
  for (size_t k = 0; k < t.size(); k += 3) mean_ += Bands(t[k], t[k + 1], t[k + 2]);
  mean_ = mean_ / double(t.size() / 3);
}

int Texture::width() const {
  return levels_[0].width;
}
int Texture::height() const {
  return levels_[0].height;
}
Bands Texture::mean() const {
  return mean_;
}

// ---- Lookups ----

Bands Texture::texel(const Level &level, long long i, long long j) const {
  return fetch(LevelView{level.width, level.height, level.texels.data(), wrap_}, i, j);
}

Bands Texture::bilinear(const Level &level, double u, double v) const {
  const LevelView view{level.width, level.height, level.texels.data(), wrap_};
  return interpolate(view, locate(view, u, v));
}

Bands Texture::bilinear(double u, double v) const {
  return bilinear(levels_[0], u, v);
}

Bands Texture::filtered(double u, double v, double footprint) const {
  // A level's texel width is taken along its longer side, so a footprint
  // never spans more than about one texel of the chosen level (no aliasing).
  auto texelWidth = [&](size_t level) { return 1.0 / std::max(levels_[level].width, levels_[level].height); };
  if (!(footprint > texelWidth(0))) return bilinear(u, v);
  size_t level = 0;
  while (level + 1 < levels_.size() && footprint >= texelWidth(level + 1)) ++level;
  if (level + 1 == levels_.size()) return bilinear(levels_[level], u, v);
  // Blend by where the footprint lies between the two texel widths in log2,
  // so the weight is continuous as the footprint grows through a level.
  const double t = std::log(footprint / texelWidth(level)) / std::log(texelWidth(level + 1) / texelWidth(level));
  return (1 - t) * bilinear(levels_[level], u, v) + t * bilinear(levels_[level + 1], u, v);
}

// The element's mean reflectance ρ̄ of C&W eq. 9.11, integrated rather than
// sampled at the centroid: a sample would alias texture detail into the
// radiosity solution and break ρ̄ = mean of ρ(x) over the element, on which
// the render-time ratio ρ(x)/ρ̄ relies.
//
// Rule: the exact integral of the bilinear reconstruction over the polygon
// (cell-by-cell clipping and Green's-theorem moments, integrateBilinear), on
// the finest level where the polygon meets at most kMaxAverageCells cells, so
// the cost is bounded (measured: ~50 µs for a polygon over 30 × 40 texels,
// ~220 µs at the cap, whatever the polygon's size).
// Error: on level 0 none beyond rounding (~1e-15). On a coarser level every
// texel is the exact mean of the finest level over its square, so interior
// cells are right and the error lives in the band of cells the boundary
// crosses, ~4/√kMaxAverageCells ≈ 6% of the area. It is small unless the
// texture has detail exactly along the polygon's edge at the scale of the
// coarse texels. Measured on 512² textures and a quad over most of them,
// against the finest level, in units of the range: 4e-7 for a sharp edge
// crossing the boundary, 3e-5 for noise, 2e-7 for a checkerboard (these three
// in texture_test), and 1.3e-2 for the adversarial case of a bright rim 4–16
// texels wide just inside the boundary (a one-off check). A polygon tiling the whole square, with either wrap mode, is
// exact on every level: each level's reconstruction integrates to its mean.
Bands Texture::average(std::span<const std::array<double, 2>> polygon) const {
  if (polygon.empty()) throw std::invalid_argument("Texture::average: empty polygon");
  Polygon uv(polygon.begin(), polygon.end());
  if (wrap_ == TextureWrap::Repeat && std::isfinite(uv[0][0]) && std::isfinite(uv[0][1])) {
    // Whole periods change nothing; moving near the origin keeps precision.
    const double du = std::floor(uv[0][0]), dv = std::floor(uv[0][1]);
    for (Point &p : uv) p = {p[0] - du, p[1] - dv};
  }
  const double area = uv.size() < 3 ? 0 : std::abs(signedArea(uv));
  if (!std::isfinite(area) || area * width() * height() <= kNegligibleTexelArea)
    return bilinear(polygon[0][0], polygon[0][1]);
  double uMin = uv[0][0], uMax = uMin, vMin = uv[0][1], vMax = vMin;
  for (const Point &p : uv)
    uMin = std::min(uMin, p[0]), uMax = std::max(uMax, p[0]), vMin = std::min(vMin, p[1]), vMax = std::max(vMax, p[1]);
  size_t level = 0;
  while (level + 1 < levels_.size() &&
         cellsMet(levels_[level].width, levels_[level].height, area, uMax - uMin, vMax - vMin) > kMaxAverageCells)
    ++level;
  const Level &chosen = levels_[level];
  if (chosen.width == 1 && chosen.height == 1) return texel(chosen, 0, 0);  // constant: the mean
  return integrateBilinear(LevelView{chosen.width, chosen.height, chosen.texels.data(), wrap_}, uv);
}

std::array<double, 2> Texture::gradient(double u, double v) const {
  const Level &level = levels_[0];
  const LevelView view{level.width, level.height, level.texels.data(), wrap_};
  const Cell c = locate(view, u, v);
  const double h00 = fetch(view, c.i, c.j).average(), h10 = fetch(view, c.i + 1, c.j).average();
  const double h01 = fetch(view, c.i, c.j + 1).average(), h11 = fetch(view, c.i + 1, c.j + 1).average();
  const double dhdx = (1 - c.fy) * (h10 - h00) + c.fy * (h11 - h01);
  const double dhdy = (1 - c.fx) * (h01 - h00) + c.fx * (h11 - h10);
  // x = u·w − ½ and y = (1 − v)·h − ½: rows run down while v runs up.
  return {dhdx * level.width, -dhdy * level.height};
}

}  // namespace radiant
