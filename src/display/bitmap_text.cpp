#include "display/bitmap_text.h"

#include <algorithm>
#include <cmath>

// The header defines its functions static; not all are used here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace radiant {

void Canvas::fill(int x0, int y0, int x1, int y1, const unsigned char colour[3]) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, width), y1 = std::min(y1, height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) rgb[(size_t(y) * width + x) * 3 + c] = colour[c];
}

int textWidth(const std::string &text, int scale) {
  std::string copy = text;
  return stb_easy_font_width(copy.data()) * scale;
}

int textHeight(int scale) {
  return 7 * scale;
}

void drawText(Canvas &canvas, int x, int y, const std::string &text, int scale, const unsigned char colour[3]) {
  // Each vertex: x, y, z as float and 4 colour bytes; four vertices per axis-aligned quad.
  struct Vertex {
    float x, y, z;
    unsigned char colour[4];
  };
  std::vector<Vertex> vertices(text.size() * 80 + 4);
  std::string copy = text;
  int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, vertices.data(), int(vertices.size() * sizeof(Vertex)));
  for (int q = 0; q < quads; ++q) {
    const Vertex *v = &vertices[size_t(q) * 4];
    float x0 = std::min({v[0].x, v[1].x, v[2].x, v[3].x}), x1 = std::max({v[0].x, v[1].x, v[2].x, v[3].x});
    float y0 = std::min({v[0].y, v[1].y, v[2].y, v[3].y}), y1 = std::max({v[0].y, v[1].y, v[2].y, v[3].y});
    canvas.fill(x + int(std::lround(x0 * scale)), y + int(std::lround(y0 * scale)), x + int(std::lround(x1 * scale)),
                y + int(std::lround(y1 * scale)), colour);
  }
}

}  // namespace radiant
