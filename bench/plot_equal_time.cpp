// plot_equal_time — draws the CSV of two_pass_equal_time as a PNG: RMSE
// against the converged image over the wall time each run took (its budget, or
// more where the solve alone overran it), log–log, one line per
// method. Usage: plot_equal_time results.csv plot.png [title]
//
// No plotting library: a canvas, lines and stb_easy_font labels
// (display/bitmap_text.h), written with writePngBytes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "display/bitmap_text.h"
#include "io/image.h"

using namespace radiant;

namespace {

struct Point {
  double seconds, rmse;
};

void line(Canvas &c, double x0, double y0, double x1, double y1, const unsigned char colour[3]) {
  const int steps = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
  for (int i = 0; i <= steps; ++i) {
    const double t = double(i) / steps;
    const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
    c.fill(x - 1, y - 1, x + 2, y + 2, colour);
  }
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s results.csv plot.png [title]\n", argv[0]);
    return 2;
  }
  std::ifstream in(argv[1]);
  if (!in) {
    std::fprintf(stderr, "plot_equal_time: cannot read %s\n", argv[1]);
    return 1;
  }
  std::map<std::string, std::vector<Point>> series;
  std::string row;
  std::getline(in, row);  // header: budget_s,method,solve_s,total_s,spp,rmse,…
  while (std::getline(in, row)) {
    std::vector<std::string> f;
    std::stringstream s(row);
    for (std::string field; std::getline(s, field, ',');) f.push_back(field);
    if (f.size() < 6 || f[0] == "budget_s") continue;  // short, or the header of a CSV joined on
    series[f[1]].push_back(
        {std::stod(f[3]), std::stod(f[5])});  // at the wall time taken: a solve may overrun the budget
  }
  // Several CSVs may have been joined (one per budget range): draw each line left to right.
  for (auto &[name, points] : series)
    std::sort(points.begin(), points.end(), [](const Point &a, const Point &b) { return a.seconds < b.seconds; });
  if (series.empty()) {
    std::fprintf(stderr, "plot_equal_time: no rows in %s\n", argv[1]);
    return 1;
  }
  double tMin = INFINITY, tMax = 0, eMin = INFINITY, eMax = 0;
  for (const auto &[name, points] : series)
    for (const Point &p : points)
      if (p.rmse > 0)
        tMin = std::min(tMin, p.seconds), tMax = std::max(tMax, p.seconds), eMin = std::min(eMin, p.rmse),
        eMax = std::max(eMax, p.rmse);
  tMin = std::pow(10, std::floor(std::log10(tMin))), tMax = std::pow(10, std::ceil(std::log10(tMax)));
  eMin = std::pow(10, std::floor(std::log10(eMin))), eMax = std::pow(10, std::ceil(std::log10(eMax)));

  Canvas canvas(900, 600);
  const unsigned char white[3] = {255, 255, 255}, grey[3] = {200, 200, 200}, black[3] = {0, 0, 0};
  canvas.fill(0, 0, canvas.width, canvas.height, white);
  const int left = 90, right = 720, top = 50, bottom = 530;
  auto X = [&](double t) { return left + (right - left) * std::log(t / tMin) / std::log(tMax / tMin); };
  auto Y = [&](double e) { return bottom - (bottom - top) * std::log(e / eMin) / std::log(eMax / eMin); };
  for (double t = tMin; t <= tMax * 1.0001; t *= 10) {
    line(canvas, X(t), top, X(t), bottom, grey);
    char label[32];
    std::snprintf(label, sizeof label, "%g s", t);
    drawText(canvas, int(X(t)) - textWidth(label, 2) / 2, bottom + 10, label, 2, black);
  }
  for (double e = eMin; e <= eMax * 1.0001; e *= 10) {
    line(canvas, left, Y(e), right, Y(e), grey);
    char label[32];
    std::snprintf(label, sizeof label, "%g", e);
    drawText(canvas, left - 10 - textWidth(label, 2), int(Y(e)) - textHeight(2) / 2, label, 2, black);
  }
  line(canvas, left, bottom, right, bottom, black), line(canvas, left, top, left, bottom, black);
  drawText(canvas, left, 15, argc > 3 ? argv[3] : "RMSE against the converged image, equal time", 2, black);
  static const unsigned char palette[][3] = {{31, 119, 180},  {255, 127, 14}, {44, 160, 44},   {214, 39, 40},
                                             {148, 103, 189}, {140, 86, 75},  {227, 119, 194}, {188, 189, 34},
                                             {23, 190, 207},  {127, 127, 127}};
  constexpr int kColours = int(sizeof palette / sizeof palette[0]);
  int index = 0;
  for (const auto &[name, points] : series) {
    const unsigned char *colour = palette[index % kColours];
    for (size_t i = 0; i + 1 < points.size(); ++i)
      if (points[i].rmse > 0 && points[i + 1].rmse > 0)
        line(canvas, X(points[i].seconds), Y(points[i].rmse), X(points[i + 1].seconds), Y(points[i + 1].rmse), colour);
    for (const Point &p : points)
      if (p.rmse > 0)
        canvas.fill(int(X(p.seconds)) - 4, int(Y(p.rmse)) - 4, int(X(p.seconds)) + 5, int(Y(p.rmse)) + 5, colour);
    canvas.fill(right + 20, top + 30 * index + 4, right + 50, top + 30 * index + 10, colour);
    drawText(canvas, right + 58, top + 30 * index, name, 2, black);
    ++index;
  }
  writePngBytes(canvas.rgb, canvas.width, canvas.height, argv[2]);
  std::fprintf(stderr, "plot_equal_time: wrote %s\n", argv[2]);
  return 0;
}
