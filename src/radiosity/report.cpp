#include "radiosity/report.h"

#include <fmt/format.h>

#include <fstream>

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

void writeSurfaceReport(const Solution &s, const Scene &scene, const std::string &path) {
  struct Totals {
    double area = 0;
    Bands radiosity, irradiance;
  };
  std::vector<Totals> perObject(scene.objects.size());
  for (uint32_t e = 0; e < s.elementCount(); ++e) {
    const Patch &patch = s.mesh.patchOf(e);
    if (patch.object >= perObject.size()) continue;
    Totals &t = perObject[patch.object];
    double a = s.mesh.elements[e].area;
    t.area += a;
    t.radiosity += s.displayRadiosity(e) * a;
    // The ambient term stands for radiosity not yet shot: it arrives as
    // irradiance too, so that the reported B = E + ρH holds (progressive).
    t.irradiance += (s.irradiance[e] + s.ambient) * a;
  }
  std::string csv =
      "object,area_m2,radiosity_R_W_m2,radiosity_G_W_m2,radiosity_B_W_m2,irradiance_R_W_m2,irradiance_G_W_m2,"
      "irradiance_B_W_m2,luminance_cd_m2,illuminance_lux\n";
  for (size_t o = 0; o < perObject.size(); ++o) {
    const Totals &t = perObject[o];
    if (t.area <= 0) continue;
    Bands b = t.radiosity / t.area, h = t.irradiance / t.area;
    // Lambertian: radiance = B/π; photometric = 683 lm/W × luminance-weighted radiometric value.
    double luminance = kLuminousEfficacy * b.luminance() / kPi;
    double illuminance = kLuminousEfficacy * h.luminance();
    csv += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n",
                       csvField(scene.objects[o].name), t.area, b[0], b[1], b[2], h[0], h[1], h[2], luminance,
                       illuminance);
  }
  writeAtomically(path, [&](const std::string &temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << csv;
    out.close();
    if (!out) throw std::runtime_error("write failed");
  });
}

}  // namespace radiant
