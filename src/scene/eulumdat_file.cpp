// EULUMDAT (.ldt) photometric files (docs/luminaires.md#photometric-files).
//
// Stockmar, "EULUMDAT – ein Leuchtendatenformat für den europäischen
// Beleuchtungsplaner" (Licht '90) and EULUMDAT/2 (CIBSE 1998): one field per
// line in a fixed order —
//
//    1 company/format   2 Ityp    3 Isym (0–4)   4 Mc (C planes in 360°)
//    5 Dc               6 Ng (γ angles per plane)   7 Dg
//    8 report number    9 luminaire name   10 luminaire number
//   11 file name       12 date/user   13–21 dimensions (mm)
//   22 DFF (%)         23 LORL (%)    24 conversion factor   25 tilt
//   26 n, the lamp sets, then six lines per set: number of lamps, lamp type,
//      total flux (lm), colour temperature, colour rendering, wattage
//   then 10 direct ratios, the Mc C angles, the Ng γ angles and the
//   intensities in cd/klm of the stored planes, Ng per plane:
//   Isym 0 all Mc planes; 1 one (rotational symmetry); 2 C0…C180 (Mc/2 + 1);
//   3 C90…C270 (Mc/2 + 1); 4 C0…C90 (Mc/4 + 1).
//
// Intensity (cd) = value × Σ lamp sets' total flux / 1000 × conversion
// factor. A negative number of lamps marks absolute photometry (the 2009
// agreement of DIAL, Lighting Analysts and Ashdown); the sign is not part of
// the product, which gives the candela either way, and the flux field is the
// set's total, so the lamp count does not multiply it. The numeric
// sections after line 26 are read as numbers separated by whitespace, so a
// writer that puts several on one line is read too. Every error names the
// line and its field.

#include <cmath>

#include "scene/photometry_detail.h"
#include "util/parse_number.h"

namespace radiant {
namespace {

using namespace photometry_detail;

constexpr int64_t kMaxLampSets = 1000;

class Fields {
 public:
  explicit Fields(TextCursor &in) : in_(in) {}

  std::string_view text(const std::string &name) {
    std::string_view line;
    if (!in_.nextLine(line))
      throw InputError(in_.here(), "the EULUMDAT file ends at line " + std::to_string(in_.line()) + ": expected line " +
                                       std::to_string(in_.line() + 1) + ", " + name);
    return trim(line);
  }
  double decimal(const std::string &name) {
    std::string_view t = text(name);
    double value;
    if (!parseDecimal(t, value))
      throw InputError(in_.here(),
                       "line " + std::to_string(in_.line()) + ", " + name + ": expected a number, found " + quoted(t));
    return value;
  }
  int64_t integer(const std::string &name, int64_t low, int64_t high) {
    std::string_view t = text(name);
    int64_t value;
    double decimal;
    if (!parseInteger(t, value)) {
      if (!parseDecimal(t, decimal) || decimal != std::floor(decimal) || std::abs(decimal) > 1e15)
        throw InputError(in_.here(), "line " + std::to_string(in_.line()) + ", " + name +
                                         ": expected an integer, found " + quoted(t));
      value = static_cast<int64_t>(decimal);
    }
    if (value < low || value > high)
      throw InputError(in_.here(), "line " + std::to_string(in_.line()) + ", " + name + ", is " +
                                       std::to_string(value) + ": expected " + std::to_string(low) + " to " +
                                       std::to_string(high));
    return value;
  }

 private:
  TextCursor &in_;
};

}  // namespace

std::shared_ptr<const PhotometricDistribution> readEulumdatFile(const std::string &path) {
  const std::string text = readBoundedFile(path, "EULUMDAT", {});
  if (photometricFormatOf(text) == PhotometricFormat::Ies)
    throw InputError({path, 1, 0, ""},
                     "this is an IES LM-63 file, not a EULUMDAT file (it has a TILT= line or an IESNA first line): "
                     "read it as IES (\"ies\" in a JSON scene)");
  TextCursor in(path, text);
  Fields fields(in);

  std::string company(fields.text("the company identification").substr(0, 240));
  fields.integer("the type indicator Ityp", 0, 3);
  int64_t symmetry = fields.integer("the symmetry indicator Isym", 0, 4);
  int64_t planeCount = fields.integer("the number Mc of C planes", 1, kMaxPhotometricAnglesPerAxis);
  fields.decimal("the distance Dc between C planes");
  int64_t gammaCount = fields.integer("the number Ng of intensities per C plane", 1, kMaxPhotometricAnglesPerAxis);
  fields.decimal("the distance Dg between intensities");
  fields.text("the measurement report number");
  std::string luminaire(fields.text("the luminaire name").substr(0, 240));
  fields.text("the luminaire number");
  fields.text("the file name");
  fields.text("the date and user");
  for (const char *name :
       {"the length or diameter of the luminaire", "the width of the luminaire", "the height of the luminaire",
        "the length or diameter of the luminous area", "the width of the luminous area",
        "the height of the luminous area at C0", "the height of the luminous area at C90",
        "the height of the luminous area at C180", "the height of the luminous area at C270"})
    fields.text(name);  // dimensions: not used, and some writers leave them blank
  fields.decimal("the downward flux fraction DFF");
  fields.decimal("the light output ratio LORL");
  double conversion = fields.decimal("the conversion factor for luminous intensities");
  if (conversion <= 0)
    throw InputError(in.here(), "line " + std::to_string(in.line()) +
                                    ", the conversion factor for luminous intensities: expected a positive number");
  fields.decimal("the tilt of the luminaire during measurement");
  int64_t lampSets = fields.integer("the number n of lamp sets", 1, kMaxLampSets);
  double flux = 0;
  std::string lampType;
  for (int64_t set = 1; set <= lampSets; ++set) {
    std::string ofSet = " of lamp set " + std::to_string(set);
    fields.integer("the number of lamps" + ofSet + " (negative: absolute photometry)", -1000000, 1000000);
    std::string type(fields.text("the type of lamps" + ofSet));
    if (set == 1) lampType = type.substr(0, 240);
    double setFlux = fields.decimal("the total luminous flux" + ofSet + " (lm)");
    if (setFlux < 0)
      throw InputError(in.here(), "line " + std::to_string(in.line()) + ", the total luminous flux" + ofSet +
                                      ", is negative: expected lumens, 0 or more");
    flux += setFlux;
    fields.text("the colour temperature" + ofSet);
    fields.text("the colour rendering group or index" + ofSet);
    fields.text("the wattage including ballast" + ofSet);
  }
  for (int k = 1; k <= 10; ++k) in.decimal("direct ratio " + std::to_string(k) + " of 10");

  // The planes the file stores, by Isym.
  int64_t firstStored = 0, storedCount = planeCount;
  double firstExpected = 0, lastExpected = 360;
  const char *stored = "";
  if (symmetry == 1) {
    storedCount = 1;
  } else if (symmetry >= 2) {
    int64_t divisor = symmetry == 4 || symmetry == 3 ? 4 : 2;
    if (planeCount % divisor != 0)
      throw InputError({path, 4, 0, ""}, "line 4, the number Mc of C planes, is " + std::to_string(planeCount) +
                                             ": Isym " + std::to_string(symmetry) + " expects a multiple of " +
                                             std::to_string(divisor));
    storedCount = symmetry == 4 ? planeCount / 4 + 1 : planeCount / 2 + 1;
    firstStored = symmetry == 3 ? planeCount / 4 : 0;
    firstExpected = symmetry == 3 ? 90 : 0;
    lastExpected = symmetry == 2 ? 180 : symmetry == 3 ? 270 : 90;
    stored = symmetry == 2 ? "C0 to C180" : symmetry == 3 ? "C90 to C270" : "C0 to C90";
  }
  if (storedCount * gammaCount > kMaxPhotometricValues)
    throw InputError({path, 6, 0, ""}, std::to_string(storedCount) + " C planes of " + std::to_string(gammaCount) +
                                           " intensities: expected at most " + std::to_string(kMaxPhotometricValues) +
                                           " values");

  PhotometricBuilder builder;
  builder.file = path;
  builder.type = PhotometricType::C;
  builder.description = luminaire.empty() ? company : company.empty() ? luminaire : company + " " + luminaire;
  if (!lampType.empty()) builder.description += ", lamp " + lampType;
  std::vector<double> planes = readAngles(in, planeCount, "C angle", 0, 360, builder.horizontalAt);
  if (symmetry == 1) {
    builder.horizontalDegrees = {0};
  } else {
    builder.horizontalDegrees.assign(planes.begin() + firstStored, planes.begin() + firstStored + storedCount);
    if (symmetry >= 2 && (std::abs(builder.horizontalDegrees.front() - firstExpected) > 1e-6 ||
                          std::abs(builder.horizontalDegrees.back() - lastExpected) > 1e-6))
      throw InputError(builder.horizontalAt, "Isym " + std::to_string(symmetry) + " stores the planes " + stored +
                                                 ", but the C angles of the stored planes run from " +
                                                 std::to_string(builder.horizontalDegrees.front()) + " to " +
                                                 std::to_string(builder.horizontalDegrees.back()) +
                                                 " (does Mc match the C angles?)");
  }
  builder.verticalDegrees = readAngles(in, gammaCount, "gamma angle", 0, 180, builder.verticalAt);
  builder.candela.reserve(static_cast<size_t>(storedCount * gammaCount));
  double scale = flux / 1000 * conversion;
  if (!std::isfinite(scale)) throw InputError(in.here(), "the lamp flux times the conversion factor is not finite");
  readIntensities(in, storedCount * gammaCount, scale, "intensity (cd/klm)", builder.candela);
  in.expectEnd("the " + std::to_string(storedCount * gammaCount) + " intensities");
  return builder.build();
}

}  // namespace radiant
