// A false-colour plan of a calculation grid's illuminance (solve
// --grid-image): the grid's cells coloured by the values interpolated
// between its points (bilinear, Turbo scale of display/false_colour.h, from
// 0 to the largest value rounded up to 1, 2 or 5 × 10^k), isolux contours at
// the legend's round values (marching squares over the points), each point's
// value printed in its cell where the cell is wide enough, and the legend.
// u runs to the right, v up: point (0, 0) is the bottom-left cell.
#pragma once

#include <vector>

namespace radiant {

struct GridPlan {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;     ///< 8-bit sRGB, row-major from the top left
  double minimum = 0, maximum = 0;    ///< the colour scale, lux
  std::vector<double> contourLevels;  ///< lux, each drawn where the values cross it
  int cellPixels = 0;                 ///< the side of one cell in the image
  bool valuesPrinted = false;
};

/// `lux`: nu × nv values, point (i, j) at index j·nu + i.
GridPlan gridPlan(const std::vector<double> &lux, int nu, int nv);

}  // namespace radiant
