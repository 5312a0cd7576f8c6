// IES LM-63 photometric files (docs/luminaires.md#photometric-files).
//
// ANSI/IESNA LM-63-1995 and -2002, ANSI/IES LM-63-2019, and the older 1986
// and 1991 files: a first line naming the version (none in 1986), keyword
// lines "[KEYWORD] text" (1986: free labels), the line TILT=NONE,
// TILT=INCLUDE (the tilt table follows) or TILT=<file> (the table in a file
// beside this one), then numbers separated by whitespace or commas and
// wrapped across lines anywhere:
//
//   lamps, lumens per lamp (−1: absolute photometry), candela multiplier,
//   vertical angle count, horizontal angle count, photometric type (1 C,
//   2 B, 3 A), units (1 feet, 2 metres), width, length, height,
//   ballast factor, a version-dependent field, input watts,
//   the vertical angles, the horizontal angles, and for each horizontal
//   angle the candela values at all vertical angles.
//
// The version-dependent field is the ballast-lamp photometric factor up to
// 1995 (a multiplier like the ballast factor), "future use" in 2002 and the
// file generation type in 2019 (neither multiplies). Every error names the
// file and line and what was expected there.

#include <cctype>
#include <cmath>
#include <filesystem>

#include "scene/photometry_detail.h"

namespace radiant {
namespace {

using namespace photometry_detail;

enum class IesVersion { Lm63_1986, Lm63_1991, Lm63_1995, Lm63_2002, Lm63_2019 };

std::string upper(std::string_view text) {
  std::string out(text);
  for (char &c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

/// The tilt table: lamp-to-luminaire geometry, pair count, angles, factors.
void readTilt(TextCursor &in, PhotometricBuilder &builder) {
  int64_t geometry = in.integer("the lamp-to-luminaire geometry (1, 2 or 3)");
  if (geometry < 1 || geometry > 3)
    throw InputError(in.here(), "lamp-to-luminaire geometry " + std::to_string(geometry) + ": expected 1, 2 or 3");
  int64_t pairs = in.integer("the number of tilt angles and factors");
  if (pairs < 1 || pairs > kMaxPhotometricAnglesPerAxis)
    throw InputError(in.here(), std::to_string(pairs) + " tilt angles: expected 1 to " +
                                    std::to_string(kMaxPhotometricAnglesPerAxis));
  InputLocation first;
  builder.tiltDegrees = readAngles(in, pairs, "tilt angle", 0, 180, first);
  readIntensities(in, pairs, 1.0, "tilt factor", builder.tiltFactors);
}

struct Keywords {
  std::string luminaire, catalogue, manufacturer, lamp, firstLabel;
};

std::string describe(const Keywords &k) {
  std::string text = !k.luminaire.empty() ? k.luminaire : !k.catalogue.empty() ? k.catalogue : k.firstLabel;
  if (!k.manufacturer.empty()) text = text.empty() ? k.manufacturer : k.manufacturer + " " + text;
  if (!k.lamp.empty()) text += (text.empty() ? "lamp " : ", lamp ") + k.lamp;
  if (text.size() > 240) text = text.substr(0, 240) + "...";
  return text;
}

}  // namespace

std::shared_ptr<const PhotometricDistribution> readIesFile(const std::string &path) {
  const std::string text = readBoundedFile(path, "IES", {});
  if (photometricFormatOf(text) == PhotometricFormat::Eulumdat)
    throw InputError({path, 1, 0, ""},
                     "this is a EULUMDAT file, not an IES LM-63 file (it has no TILT= line, and its lines 2 to 6 are "
                     "EULUMDAT's type, symmetry and counts): read it as EULUMDAT (\"ldt\" in a JSON scene)");
  TextCursor in(path, text);
  std::string_view line;
  if (!in.nextLine(line))
    throw InputError({path, 1, 0, ""},
                     "the IES file is empty: expected IESNA:LM-63-2002 (or another version) "
                     "or TILT= and the photometric data");

  IesVersion version = IesVersion::Lm63_1986;
  std::string first = upper(trim(line));
  bool firstIsHeader = true;
  if (first.starts_with("IESNA:LM-63-1995"))
    version = IesVersion::Lm63_1995;
  else if (first.starts_with("IESNA:LM-63-2002"))
    version = IesVersion::Lm63_2002;
  else if (first.starts_with("IES:LM-63-2019"))
    version = IesVersion::Lm63_2019;
  else if (first.starts_with("IESNA91"))
    version = IesVersion::Lm63_1991;
  else if (first.starts_with("IESNA:") || first.starts_with("IES:"))
    throw InputError(in.here(), "unknown IES version " + quoted(trim(line)) +
                                    ": expected IESNA:LM-63-1995, IESNA:LM-63-2002, IES:LM-63-2019 or IESNA91");
  else
    firstIsHeader = false;  // 1986: no version line, the first line is a label

  // Keyword lines (1986: labels) up to TILT=.
  Keywords keywords;
  std::string *lastKeyword = nullptr;
  std::string tilt;
  int tiltLine = 0;
  bool haveLine = !firstIsHeader;  // the first line still to be looked at
  for (;;) {
    if (!haveLine && !in.nextLine(line))
      throw InputError(in.here(),
                       "the file ends before its TILT= line: expected TILT=NONE, TILT=INCLUDE or "
                       "TILT=<file> after the keyword lines");
    haveLine = false;
    std::string_view t = trim(line);
    std::string_view afterTilt = trim(t.substr(std::min<size_t>(4, t.size())));
    if (upper(t.substr(0, 4)) == "TILT" && !afterTilt.empty() && afterTilt.front() == '=') {
      tilt = std::string(trim(afterTilt.substr(1)));
      tiltLine = in.line();
      break;
    }
    if (!t.empty() && t.front() == '[') {
      size_t close = t.find(']');
      if (close == std::string_view::npos)
        throw InputError(in.here(), "expected a keyword line [KEYWORD] text, found " + quoted(t) + " (no ']')");
      std::string key = upper(t.substr(1, close - 1));
      std::string value(trim(t.substr(close + 1)));
      if (key == "MORE") {
        if (lastKeyword && !value.empty() && lastKeyword->size() < 1000) *lastKeyword += " " + value;
        continue;
      }
      lastKeyword = key == "LUMINAIRE" ? &keywords.luminaire
                    : key == "LUMCAT"  ? &keywords.catalogue
                    : key == "MANUFAC" ? &keywords.manufacturer
                    : key == "LAMP"    ? &keywords.lamp
                                       : nullptr;
      if (lastKeyword) *lastKeyword = value.substr(0, 1000);
    } else if (keywords.firstLabel.empty() && !t.empty()) {
      keywords.firstLabel = std::string(t.substr(0, 240));
    }
  }

  PhotometricBuilder builder;
  builder.file = path;
  builder.description = describe(keywords);
  std::string tiltWord = upper(tilt);
  if (tiltWord == "INCLUDE") {
    readTilt(in, builder);
  } else if (tiltWord != "NONE") {
    if (tilt.empty()) throw InputError(in.here(), "expected TILT=NONE, TILT=INCLUDE or TILT=<file>, found TILT=");
    std::filesystem::path tiltPath = std::filesystem::path(path).parent_path() / tilt;
    std::string tiltText = readBoundedFile(tiltPath.string(), "IES tilt", {path, tiltLine, 0, ""});
    TextCursor tiltIn(tiltPath.string(), tiltText);
    readTilt(tiltIn, builder);
    tiltIn.expectEnd("the tilt table");
  }

  in.integer("the number of lamps");
  in.decimal("the lumens per lamp (-1 for absolute photometry)");
  double multiplier = in.decimal("the candela multiplier");
  if (multiplier < 0) throw InputError(in.here(), "the candela multiplier is negative: expected 0 or more");
  int64_t verticalCount = in.integer("the number of vertical angles");
  if (verticalCount < 1 || verticalCount > kMaxPhotometricAnglesPerAxis)
    throw InputError(in.here(), std::to_string(verticalCount) + " vertical angles: expected 1 to " +
                                    std::to_string(kMaxPhotometricAnglesPerAxis));
  int64_t horizontalCount = in.integer("the number of horizontal angles");
  if (horizontalCount < 1 || horizontalCount > kMaxPhotometricAnglesPerAxis)
    throw InputError(in.here(), std::to_string(horizontalCount) + " horizontal angles: expected 1 to " +
                                    std::to_string(kMaxPhotometricAnglesPerAxis));
  if (verticalCount * horizontalCount > kMaxPhotometricValues)
    throw InputError(in.here(), std::to_string(verticalCount) + " by " + std::to_string(horizontalCount) +
                                    " candela values: expected at most " + std::to_string(kMaxPhotometricValues));
  int64_t type = in.integer("the photometric type (1 C, 2 B, 3 A)");
  if (type < 1 || type > 3)
    throw InputError(in.here(), "photometric type " + std::to_string(type) + ": expected 1 (C), 2 (B) or 3 (A)");
  builder.type = type == 1 ? PhotometricType::C : type == 2 ? PhotometricType::B : PhotometricType::A;
  int64_t units = in.integer("the units type (1 feet, 2 metres)");
  if (units < 1 || units > 2)
    throw InputError(in.here(), "units type " + std::to_string(units) + ": expected 1 (feet) or 2 (metres)");
  in.decimal("the luminous opening's width");
  in.decimal("the luminous opening's length");
  in.decimal("the luminous opening's height");
  double ballastFactor = in.decimal("the ballast factor");
  if (ballastFactor < 0) throw InputError(in.here(), "the ballast factor is negative: expected 0 or more");
  double third = in.decimal(version <= IesVersion::Lm63_1995   ? "the ballast-lamp photometric factor"
                            : version == IesVersion::Lm63_2002 ? "the future-use field"
                                                               : "the file generation type");
  double scale = multiplier * ballastFactor;
  if (version <= IesVersion::Lm63_1995) {
    if (third < 0) throw InputError(in.here(), "the ballast-lamp photometric factor is negative: expected 0 or more");
    scale *= third;
  }
  if (!std::isfinite(scale)) throw InputError(in.here(), "the product of the multipliers is not a finite number");
  in.decimal("the input watts");

  builder.verticalDegrees = readAngles(in, verticalCount, "vertical angle", -180, 180, builder.verticalAt);
  builder.horizontalDegrees = readAngles(in, horizontalCount, "horizontal angle", -360, 360, builder.horizontalAt);
  builder.candela.reserve(static_cast<size_t>(verticalCount * horizontalCount));
  readIntensities(in, verticalCount * horizontalCount, scale, "candela value", builder.candela);
  in.expectEnd("the " + std::to_string(verticalCount * horizontalCount) + " candela values");
  return builder.build();
}

}  // namespace radiant
