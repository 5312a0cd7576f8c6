#include "display/false_colour.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "display/bitmap_text.h"
#include "display/emitter_mask.h"
#include "display/luminance.h"
#include "util/error.h"

namespace radiant {

namespace {

/// The smallest of 1, 2, 5 × 10^k that is ≥ v.
double niceCeiling(double v) {
  double decade = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * decade >= v * (1 - 1e-12)) return m * decade;
  return 10 * decade;
}

/// Where a value sits on the scale, 0 … 1 (clamped).
double scalePosition(double value, double minimum, double maximum, bool logarithmic) {
  double x = logarithmic ? (value > 0 ? (std::log10(value) - std::log10(minimum)) / (std::log10(maximum / minimum)) : 0)
                         : (value - minimum) / (maximum - minimum);
  return std::clamp(x, 0.0, 1.0);
}

/// Tick values: every decade on a log scale (every second … when there are many), else about five steps of 1, 2, 5 ×
/// 10^k.
std::vector<double> ticks(double minimum, double maximum, bool logarithmic) {
  std::vector<double> values;
  if (logarithmic) {
    int first = int(std::ceil(std::log10(minimum) - 1e-9)), last = int(std::floor(std::log10(maximum) + 1e-9));
    int stride = std::max(1, (last - first + 7) / 8);
    for (int k = first; k <= last; k += stride) values.push_back(std::pow(10.0, k));
  } else {
    double step = niceCeiling((maximum - minimum) / 5);
    for (double v = std::ceil(minimum / step - 1e-9) * step; v <= maximum * (1 + 1e-9); v += step)
      values.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  }
  return values;
}

/// A panel of `panelWidth` to the right of the image: the colour bar, tick marks, labels and the unit on top.
void drawLegend(Canvas &canvas, int imageWidth, const FalseColourImage &scale, bool logarithmic, const char *unit,
                int textScale) {
  const unsigned char background[3] = {24, 24, 24}, white[3] = {235, 235, 235};
  canvas.fill(imageWidth, 0, canvas.width, canvas.height, background);
  const int margin = 4 * textScale, barWidth = 10 * textScale, text = textHeight(textScale);
  const int barX = imageWidth + margin, top = margin + text + margin, bottom = canvas.height - margin - text / 2;
  drawText(canvas, barX, margin, unit, textScale, white);
  if (bottom <= top) return;
  for (int y = top; y < bottom; ++y) {
    unsigned char colour[3];
    turboColour(1.0 - double(y - top) / std::max(1, bottom - top - 1), colour);
    canvas.fill(barX, y, barX + barWidth, y + 1, colour);
  }
  for (double value : ticks(scale.minimum, scale.maximum, logarithmic)) {
    double x = scalePosition(value, scale.minimum, scale.maximum, logarithmic);
    int y = top + int(std::lround((1 - x) * (bottom - top - 1)));
    canvas.fill(barX + barWidth, y, barX + barWidth + 3 * textScale, y + textScale, white);
    drawText(canvas, barX + barWidth + 5 * textScale, y - text / 2, fmt::format("{:g}", value), textScale, white);
  }
}

}  // namespace

void turboColour(double x, unsigned char rgb[3]) {
  // Turbo, polynomial approximation by Ruofei Du (Google, 2019, Apache-2.0) of Anton Mikhailov's map.
  static constexpr double kRed[6] = {0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943};
  static constexpr double kGreen[6] = {0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604};
  static constexpr double kBlue[6] = {0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973};
  x = std::clamp(x, 0.0, 1.0);
  const double powers[6] = {1, x, x * x, x * x * x, x * x * x * x, x * x * x * x * x};
  const double *coefficients[3] = {kRed, kGreen, kBlue};
  for (int c = 0; c < 3; ++c) {
    double v = 0;
    for (int k = 0; k < 6; ++k) v += coefficients[c][k] * powers[k];
    rgb[c] = static_cast<unsigned char>(std::lround(255 * std::clamp(v, 0.0, 1.0)));
  }
}

FalseColourImage falseColour(const Image &image, const FalseColourSettings &settings) {
  const size_t pixels = size_t(image.width) * image.height;
  std::vector<double> values(pixels);
  for (size_t p = 0; p < pixels; ++p) values[p] = luminanceCdPerM2(&image.rgb[3 * p]);  // lux for irradiance

  FalseColourImage result;
  if (settings.minimum && settings.maximum) {
    result.minimum = *settings.minimum, result.maximum = *settings.maximum;
  } else {
    const std::vector<uint8_t> emitter = emitterPixelMask(image);
    double largest = 0;
    for (size_t p = 0; p < pixels; ++p)
      if (!emitter[p] && std::isfinite(values[p])) largest = std::max(largest, values[p]);
    if (!(largest > 0)) largest = 1;
    result.maximum =
        settings.logarithmic ? std::pow(10.0, std::ceil(std::log10(largest) - 1e-9)) : niceCeiling(largest);
    result.minimum = settings.logarithmic ? result.maximum / 1000 : 0;
  }
  if (!(result.minimum < result.maximum) || !std::isfinite(result.maximum))
    throw InputError(InputLocation::ofParameter("range"),
                     fmt::format("MIN must be below MAX, got {:g},{:g}", result.minimum, result.maximum));
  if (settings.logarithmic && !(result.minimum > 0))
    throw InputError(InputLocation::ofParameter("range"),
                     fmt::format("a --log scale needs MIN > 0, got {:g}", result.minimum));

  const bool luminance = settings.quantity == FalseColourQuantity::Luminance;
  const char *unit = luminance ? "cd/m2" : "lux";
  const int textScale = std::max(1, image.height / 160);
  int panelWidth = 0;
  if (settings.legend) {
    int widest = textWidth(unit, textScale);
    for (double v : ticks(result.minimum, result.maximum, settings.logarithmic))
      widest = std::max(widest, 15 * textScale + textWidth(fmt::format("{:g}", v), textScale));
    panelWidth = 4 * textScale + std::max(widest, 10 * textScale) + 6 * textScale;
  }
  Canvas canvas(image.width + panelWidth, image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      double v = values[size_t(y) * image.width + x];
      unsigned char *out = &canvas.rgb[(size_t(y) * canvas.width + x) * 3];
      if (!std::isfinite(v)) {
        out[0] = 255, out[1] = 0, out[2] = 255;
      } else {
        turboColour(scalePosition(v, result.minimum, result.maximum, settings.logarithmic), out);
      }
    }
  if (settings.legend) drawLegend(canvas, image.width, result, settings.logarithmic, unit, textScale);
  result.width = canvas.width, result.height = canvas.height;
  result.rgb = std::move(canvas.rgb);
  return result;
}

}  // namespace radiant
