#include "radiosity/report.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"

namespace radiant {

namespace {
/// CSV quoting (RFC 4180): names may hold commas or quotes.
std::string csvField(const std::string &s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}
}  // namespace

namespace {

/// Area-weighted sums over one object's elements in one solution.
struct ObjectTotals {
  double area = 0;
  Bands radiosity, irradiance;
};

std::vector<ObjectTotals> objectTotals(const Solution &s, size_t objectCount) {
  std::vector<ObjectTotals> perObject(objectCount);
  for (uint32_t e = 0; e < s.elementCount(); ++e) {
    const Patch &patch = s.mesh.patchOf(e);
    if (patch.object >= perObject.size()) continue;
    ObjectTotals &t = perObject[patch.object];
    double a = s.mesh.elements[e].area;
    t.area += a;
    t.radiosity += s.displayRadiosity(e) * a;
    // The ambient term stands for radiosity not yet shot: it arrives as
    // irradiance too, so that the reported B = E + ρH holds (progressive).
    t.irradiance += (s.irradiance[e] + s.ambient) * a;
  }
  return perObject;
}

}  // namespace

void writeSurfaceReport(const Solution &solution, const Scene &scene, const std::string &path) {
  writeSurfaceReport(std::span<const Solution>(&solution, 1), scene, path, WhiteBalance::None);
}

void writeSurfaceReport(std::span<const Solution> passes, const Scene &scene, const std::string &path,
                        WhiteBalance balance) {
  if (passes.size() != size_t(scene.spectral.enabled() ? scene.spectral.passCount() : 1))
    throw std::logic_error("writeSurfaceReport: one solution per spectral pass expected");
  std::vector<std::vector<ObjectTotals>> totals;
  for (const Solution &s : passes) totals.push_back(objectTotals(s, scene.objects.size()));
  const bool spectral = scene.spectral.enabled();
  const int bands = spectral ? int(scene.spectral.wavelengths.size()) : kBandCount;
  std::vector<Vec3> toRgb, toXyz;
  double perNm = 1;
  if (spectral) {
    BandColourMatching matching(scene.spectral.wavelengths);
    toRgb = matching.linearSrgbWeights(balance);
    for (int i = 0; i < bands; ++i) toXyz.push_back(matching.xyzWeight(i));
    perNm = 1.0 / cieYIntegral(int(std::ceil(scene.spectral.wavelengths.front())),
                               int(std::floor(scene.spectral.wavelengths.back())));
  }

  std::string csv =
      "object,area_m2,radiosity_R_W_m2,radiosity_G_W_m2,radiosity_B_W_m2,irradiance_R_W_m2,irradiance_G_W_m2,"
      "irradiance_B_W_m2,luminance_cd_m2,illuminance_lux";
  for (int i = 0; spectral && i < bands; ++i)
    csv += fmt::format(",radiosity_{:g}nm_W_m2_nm", scene.spectral.wavelengths[i]);
  csv += "\n";
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const double area = totals[0][o].area;
    if (area <= 0) continue;
    // The object's mean B and H per band: R, G, B, or one value per wavelength
    // (each pass over its own mesh; the areas agree to rounding).
    std::vector<double> b(bands), h(bands);
    for (int i = 0; i < bands; ++i) {
      const ObjectTotals &t = totals[i / kBandCount][o];
      b[i] = t.radiosity[i % kBandCount] / t.area;
      h[i] = t.irradiance[i % kBandCount] / t.area;
    }
    Vec3 rgbB{b[0], b[1], b[2]}, rgbH{h[0], h[1], h[2]};
    double yB = Bands(b[0], b[1], b[2]).luminance(), yH = Bands(h[0], h[1], h[2]).luminance();
    if (spectral) {
      rgbB = rgbH = Vec3{};
      yB = yH = 0;
      for (int i = 0; i < bands; ++i) {
        rgbB += toRgb[i] * b[i], rgbH += toRgb[i] * h[i];
        yB += toXyz[i].y * b[i], yH += toXyz[i].y * h[i];
      }
    }
    // Lambertian: radiance = B/π; photometric = 683 lm/W × luminance-weighted
    // radiometric value. For spectral scenes Y is always the unbalanced ȳ
    // integral: a white balance changes colours for display, not photometry.
    csv += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}",
                       csvField(scene.objects[o].name), area, rgbB.x, rgbB.y, rgbB.z, rgbH.x, rgbH.y, rgbH.z,
                       kLuminousEfficacy * yB / kPi, kLuminousEfficacy * yH);
    for (int i = 0; spectral && i < bands; ++i) csv += fmt::format(",{:.9g}", b[i] * perNm);
    csv += "\n";
  }
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << csv;
    out.close();
    if (!out) throw std::runtime_error("write failed");
  });
}

}  // namespace radiant
