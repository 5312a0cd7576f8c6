// Text for legends, drawn into an 8-bit RGB buffer with stb_easy_font (the
// Debian libstb-dev header): ASCII only, a 7-unit-high segment font, scaled by
// whole pixels so the strokes stay sharp.
#pragma once

#include <string>
#include <vector>

namespace radiant {

/// An 8-bit RGB canvas, row-major from the top left.
struct Canvas {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  Canvas(int w, int h) : width(w), height(h), rgb(size_t(w) * h * 3, 0) {}
  /// Fills [x0, x1) × [y0, y1), clipped to the canvas.
  void fill(int x0, int y0, int x1, int y1, const unsigned char colour[3]);
};

/// Width and height in canvas pixels of `text` drawn at `scale` (cap height ≈ 7 · scale).
int textWidth(const std::string &text, int scale);
int textHeight(int scale);
/// Draws `text` with its top-left corner at (x, y), clipped to the canvas.
void drawText(Canvas &canvas, int x, int y, const std::string &text, int scale, const unsigned char colour[3]);

}  // namespace radiant
