#include "display/grid_plan.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "display/bitmap_text.h"
#include "display/false_colour.h"
#include "io/image.h"
#include "util/spectrum.h"

namespace radiant {

namespace {

/// The plan's longer side, in pixels, before the legend; cells are square.
constexpr int kPlanPixels = 768;
constexpr int kMaxCellPixels = 96;

/// Round contour levels strictly inside (minimum, maximum): steps of 1, 2 or 5 × 10^k, about six of them.
std::vector<double> contourLevels(double minimum, double maximum) {
  std::vector<double> levels;
  if (!(maximum > minimum)) return levels;
  const double raw = (maximum - minimum) / 6;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * decade;
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= raw) {
      step = m * decade;
      break;
    }
  for (double v = std::floor(minimum / step + 1) * step; v < maximum * (1 - 1e-9); v += step) levels.push_back(v);
  return levels;
}

struct PixelCanvas {
  int width, height;
  std::vector<unsigned char> &rgb;
  void set(int x, int y, const unsigned char colour[3]) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::copy(colour, colour + 3, &rgb[(size_t(y) * width + x) * 3]);
  }
  /// A 1-pixel line (DDA), clipped to `clipWidth` (the plan, not the legend).
  void line(double x0, double y0, double x1, double y1, int clipWidth, const unsigned char colour[3]) {
    const int steps = int(std::ceil(std::max(std::abs(x1 - x0), std::abs(y1 - y0)))) + 1;
    for (int s = 0; s <= steps; ++s) {
      const double t = double(s) / steps;
      const int x = int(std::floor(x0 + (x1 - x0) * t)), y = int(std::floor(y0 + (y1 - y0) * t));
      if (x < clipWidth) set(x, y, colour);
    }
  }
};

}  // namespace

GridPlan gridPlan(const std::vector<double> &lux, int nu, int nv) {
  GridPlan plan;
  plan.cellPixels = std::clamp(kPlanPixels / std::max(nu, nv), 1, kMaxCellPixels);
  const int c = plan.cellPixels, width = nu * c, height = nv * c;
  auto value = [&](int i, int j) {
    return lux[size_t(std::clamp(j, 0, nv - 1)) * nu + size_t(std::clamp(i, 0, nu - 1))];
  };
  // Pixel centres to grid coordinates: point (i, j) sits at ((i + ½)c, height − (j + ½)c).
  Image image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double s = (x + 0.5) / c - 0.5, t = (height - y - 0.5) / c - 0.5;
      const int i = int(std::floor(s)), j = int(std::floor(t));
      const double fs = std::clamp(s - i, 0.0, 1.0), ft = std::clamp(t - j, 0.0, 1.0);
      const double v = (1 - ft) * ((1 - fs) * value(i, j) + fs * value(i + 1, j)) +
                       ft * ((1 - fs) * value(i, j + 1) + fs * value(i + 1, j + 1));
      // Equal bands: the Rec.709 weights sum to 1, so false colour reads v lux back.
      float *p = image.pixel(x, y);
      p[0] = p[1] = p[2] = float(v / kLuminousEfficacy);
    }
  FalseColourSettings settings;
  settings.quantity = FalseColourQuantity::Illuminance;
  settings.legend = true;
  FalseColourImage coloured = falseColour(image, settings);
  plan.width = coloured.width, plan.height = coloured.height;
  plan.minimum = coloured.minimum, plan.maximum = coloured.maximum;
  Canvas text(plan.width, plan.height);
  text.rgb = std::move(coloured.rgb);
  PixelCanvas canvas{plan.width, plan.height, text.rgb};

  // Isolux contours: marching squares over the squares whose corners are four neighbouring points.
  double lowest = lux.empty() ? 0 : *std::min_element(lux.begin(), lux.end());
  double highest = lux.empty() ? 0 : *std::max_element(lux.begin(), lux.end());
  plan.contourLevels = contourLevels(std::max(lowest, plan.minimum), std::min(highest, plan.maximum));
  const unsigned char ink[3] = {0, 0, 0};
  for (double level : plan.contourLevels)
    for (int j = 0; j + 1 < nv; ++j)
      for (int i = 0; i + 1 < nu; ++i) {
        // Corners counter-clockwise from (i, j); a crossing on each edge whose ends straddle the level.
        const std::array<std::array<int, 2>, 4> corner = {{{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}}};
        std::array<double, 2> points[4];
        int count = 0;
        for (int e = 0; e < 4; ++e) {
          const auto &a = corner[size_t(e)], &b = corner[size_t((e + 1) % 4)];
          const double va = value(a[0], a[1]), vb = value(b[0], b[1]);
          if ((va < level) == (vb < level)) continue;
          const double t = (level - va) / (vb - va);
          const double gi = a[0] + t * (b[0] - a[0]), gj = a[1] + t * (b[1] - a[1]);
          points[count++] = {(gi + 0.5) * c, height - (gj + 0.5) * c};
        }
        // Two crossings: one segment. Four (a saddle): pair them by the centre's side, so lines never cross.
        if (count == 2) canvas.line(points[0][0], points[0][1], points[1][0], points[1][1], width, ink);
        if (count == 4) {
          const double centre = 0.25 * (value(i, j) + value(i + 1, j) + value(i + 1, j + 1) + value(i, j + 1));
          const bool firstAbove = value(i, j) >= level;
          const int pairing = (centre >= level) == firstAbove ? 1 : 0;
          if (pairing == 0) {
            canvas.line(points[0][0], points[0][1], points[1][0], points[1][1], width, ink);
            canvas.line(points[2][0], points[2][1], points[3][0], points[3][1], width, ink);
          } else {
            canvas.line(points[1][0], points[1][1], points[2][0], points[2][1], width, ink);
            canvas.line(points[3][0], points[3][1], points[0][0], points[0][1], width, ink);
          }
        }
      }

  // Each point's value in its cell, where the widest label fits with a margin.
  auto label = [](double v) { return v >= 100 ? fmt::format("{:.0f}", v) : fmt::format("{:.3g}", v); };
  int widest = 0;
  for (double v : lux) widest = std::max(widest, textWidth(label(v), 1));
  plan.valuesPrinted = widest + 4 <= c && textHeight(1) + 4 <= c;
  if (plan.valuesPrinted) {
    // As large as fits with a margin, at most 3 (labels stay smaller than the cells' colours).
    const int scale = std::clamp(std::min((c - 8) / std::max(widest, 1), c / (3 * textHeight(1))), 1, 3);
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const int x = i * c + (c - textWidth(label(value(i, j)), scale)) / 2;
        const int y = height - (j + 1) * c + (c - textHeight(scale)) / 2;
        // Dark text on the light middle of Turbo, light text on its dark ends: the cell's own colour on the
        // scale (a pixel under the label may be a contour's ink).
        unsigned char under[3];
        turboColour((value(i, j) - plan.minimum) / (plan.maximum - plan.minimum), under);
        const double brightness = 0.2126 * under[0] + 0.7152 * under[1] + 0.0722 * under[2];
        const unsigned char dark[3] = {0, 0, 0}, light[3] = {255, 255, 255};
        drawText(text, x, y, label(value(i, j)), scale, brightness > 110 ? dark : light);
      }
  }
  plan.rgb = std::move(text.rgb);
  return plan;
}

}  // namespace radiant
