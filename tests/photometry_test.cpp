// Photometric files (IES LM-63, EULUMDAT) and the distributions read from
// them: closed forms (isotropic, Lambertian), symmetric tables against the
// same luminaire written in full, the frames of types A and B, the flux of the
// interpolant by quadrature, sampling against its own density, and malformed
// files refused with their file and line.
#include "scene/photometry.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "chi_square.h"
#include "util/random.h"

namespace radiant {
namespace {

namespace fs = std::filesystem;

constexpr int kChiSquareTestsInThisFile = 3;

std::string fixture(const std::string &name) {
  return std::string(RADIANT_SOURCE_DIR) + "/tests/photometry/" + name;
}

double radians(double degrees) {
  return degrees * kPi / 180;
}

/// Type C: γ from +z, C from +x towards +y.
Vec3 typeC(double cDegrees, double gammaDegrees) {
  double c = radians(cDegrees), g = radians(gammaDegrees);
  return {std::sin(g) * std::cos(c), std::sin(g) * std::sin(c), std::cos(g)};
}
/// Type B (docs/luminaires.md): x towards V = 90°, y towards H = 90°, z the beam.
Vec3 typeB(double hDegrees, double vDegrees) {
  double h = radians(hDegrees), v = radians(vDegrees);
  return {std::cos(h) * std::sin(v), std::sin(h), std::cos(h) * std::cos(v)};
}
/// Type A: x towards V = 90°, y towards H = 90°, z the beam; the planes share the x axis.
Vec3 typeA(double hDegrees, double vDegrees) {
  double h = radians(hDegrees), v = radians(vDegrees);
  return {std::sin(v), std::cos(v) * std::sin(h), std::cos(v) * std::cos(h)};
}

/// A scratch folder of this process, removed at the end.
class ScratchFolder {
 public:
  ScratchFolder() : path_(fs::temp_directory_path() / ("radiant-photometry-test-" + std::to_string(getpid()))) {
    fs::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string write(const std::string &name, const std::string &text) const {
    std::string file = (path_ / name).string();
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }

 private:
  fs::path path_;
};

std::string readText(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Directions spread over the sphere, deterministic.
std::vector<Vec3> testDirections(int n) {
  std::vector<Vec3> directions;
  Pcg32 rng(7, 11);
  for (int k = 0; k < n; ++k) {
    double z = 2 * rng.next() - 1, phi = 2 * kPi * rng.next(), r = std::sqrt(std::max(0.0, 1 - z * z));
    directions.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  // And the axes, where the angle functions are at their edges.
  for (Vec3 axis : {Vec3{1, 0, 0}, Vec3{-1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, -1, 0}, Vec3{0, 0, 1}, Vec3{0, 0, -1}})
    directions.push_back(axis);
  return directions;
}

void expectSameDistribution(const PhotometricDistribution &a, const PhotometricDistribution &b,
                            double relativeTolerance = 1e-9) {
  double scale = std::max(a.maxCandela(), 1e-300);
  for (const Vec3 &w : testDirections(3000))
    ASSERT_NEAR(a.candela(w), b.candela(w), relativeTolerance * scale)
        << "at (" << w.x << ", " << w.y << ", " << w.z << ") of " << a.file() << " and " << b.file();
  EXPECT_NEAR(a.lumens(), b.lumens(), relativeTolerance * a.lumens());
  EXPECT_NEAR(a.maxCandela(), b.maxCandela(), relativeTolerance * scale);
}

/// ∫ candela dω by 6 × 6-point Gauss–Legendre in each cell of a web whose
/// cell edges are `azimuth` × `polar` (degrees), with the direction and the
/// solid-angle measure of the type: exact to rounding for a bilinear table.
double quadratureOverWeb(const PhotometricDistribution &d, const std::vector<double> &azimuth,
                         const std::vector<double> &polar, const std::function<Vec3(double, double)> &direction,
                         const std::function<double(double)> &measure) {
  const double x[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                       0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
  const double w[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                       0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
  double total = 0;
  for (size_t i = 0; i + 1 < azimuth.size(); ++i)
    for (size_t j = 0; j + 1 < polar.size(); ++j) {
      double a0 = azimuth[i], a1 = azimuth[i + 1], p0 = polar[j], p1 = polar[j + 1];
      for (int s = 0; s < 6; ++s)
        for (int t = 0; t < 6; ++t) {
          double a = 0.5 * (a0 + a1) + 0.5 * (a1 - a0) * x[s], p = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * x[t];
          total += w[s] * w[t] * 0.25 * radians(a1 - a0) * radians(p1 - p0) * d.candela(direction(a, p)) *
                   measure(radians(p));
        }
    }
  return total;
}

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> v;
  for (double a = from; a <= to + 1e-9; a += step) v.push_back(a);
  return v;
}

// ---- Closed forms --------------------------------------------------------------

TEST(PhotometryIes, IsotropicFileIsThousandCandelaEverywhere) {
  auto d = readIesFile(fixture("isotropic.ies"));
  EXPECT_EQ(d->type(), PhotometricType::C);
  for (const Vec3 &w : testDirections(200)) EXPECT_NEAR(d->candela(w), 1000, 1e-9);
  EXPECT_NEAR(d->lumens(), 4 * kPi * 1000, 1e-9 * 4 * kPi * 1000);
  EXPECT_EQ(d->maxCandela(), 1000);
  EXPECT_EQ(d->tiltFactor(30), 1);
  EXPECT_NE(d->description().find("Isotropic 1000 cd"), std::string::npos) << d->description();
  EXPECT_NE(d->description().find("Radiant Test Luminaires"), std::string::npos) << d->description();
  EXPECT_EQ(d->file(), fixture("isotropic.ies"));
  // Not normalised: the length of `local` does not matter.
  EXPECT_NEAR(d->candela({0, 0, 7}), 1000, 1e-9);
}

TEST(PhotometryIes, LambertianDownlightFluxIsPiI0WithinTheInterpolationError) {
  // I(γ) = 800 cos γ tabulated every 5° on 0…90 (LM-63-1995). Linear
  // interpolation of a concave function lies below it by at most Δ²/8·max|I''|
  // = Δ²/8·800, so π·800 − 2π·Δ²/8·800 ≤ Φ ≤ π·800.
  auto d = readIesFile(fixture("lambertian_downlight.ies"));
  const double i0 = 800, delta = radians(5);
  EXPECT_LE(d->lumens(), kPi * i0 + 1e-6);
  EXPECT_GE(d->lumens(), kPi * i0 - 2 * kPi * delta * delta / 8 * i0);
  EXPECT_NEAR(d->candela({0, 0, 1}), i0, 1e-9);
  EXPECT_NEAR(d->candela(typeC(123, 60)), i0 / 2, 1e-6);
  EXPECT_EQ(d->candela({0, 0, -1}), 0);     // above the horizontal: nothing
  EXPECT_EQ(d->candela(typeC(40, 95)), 0);  // just above it
  EXPECT_NEAR(d->candela(typeC(40, 90)), 0, 1e-6);
  EXPECT_NEAR(d->maxCandela(), i0, 1e-9);
}

TEST(PhotometryIes, LumensAreTheFluxOfTheInterpolatedCandela) {
  auto measureC = [](double gamma) { return std::sin(gamma); };
  auto bilateral = readIesFile(fixture("bilateral_90_270.ies"));
  double q = quadratureOverWeb(*bilateral, steps(0, 360, 30), steps(0, 180, 10), typeC, measureC);
  EXPECT_NEAR(bilateral->lumens(), q, 1e-9 * q);

  auto lambert = readIesFile(fixture("lambertian_downlight.ies"));
  q = quadratureOverWeb(*lambert, {0, 360}, steps(0, 90, 5), typeC, measureC);
  EXPECT_NEAR(lambert->lumens(), q, 1e-9 * q);

  // Type B: cells in (V, H); dω = cos H dH dV.
  auto flood = readIesFile(fixture("floodlight_type_b_asymmetric.ies"));
  q = quadratureOverWeb(
      *flood, steps(-90, 90, 10), steps(-90, 90, 10), [](double v, double h) { return typeB(h, v); },
      [](double h) { return std::cos(h); });
  EXPECT_NEAR(flood->lumens(), q, 1e-9 * q);
}

TEST(PhotometryIes, UplightAndDarkFiles) {
  ScratchFolder scratch;
  // Vertical angles 90…180: nothing below the horizontal.
  auto up = readIesFile(scratch.write("uplight.ies", std::string("IESNA:LM-63-2002\nTILT=NONE\n") +
                                                         "1 -1 1 3 1 1 2 0 0 0\n1 1 10\n90 135 180\n0\n0 50 100\n"));
  EXPECT_EQ(up->candela({0, 0, 1}), 0);
  EXPECT_NEAR(up->candela({0, 0, -1}), 100, 1e-9);
  EXPECT_NEAR(up->candela(typeC(77, 135)), 50, 1e-9);
  double pdf;
  Vec3 w = up->sample(0.3, 0.6, pdf);
  EXPECT_LT(w.z, 0);
  EXPECT_GT(pdf, 0);
  // All zero: no flux, and sample() says so with pdf 0 instead of dividing by it.
  auto dark = readIesFile(scratch.write(
      "dark.ies", std::string("IESNA:LM-63-2002\nTILT=NONE\n") + "1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n0 0 0\n"));
  EXPECT_EQ(dark->lumens(), 0);
  dark->sample(0.5, 0.5, pdf);
  EXPECT_EQ(pdf, 0);
  EXPECT_EQ(dark->pdf({0, 0, 1}), 0);
}

// ---- Symmetry ------------------------------------------------------------------

TEST(PhotometryIes, QuadrantFileExpandsLikeTheFullOne) {
  expectSameDistribution(*readIesFile(fixture("quadrant.ies")), *readIesFile(fixture("quadrant_full.ies")));
}

TEST(PhotometryIes, BilateralFileExpandsLikeTheFullOneEndingBefore360) {
  // bilateral_full.ies stops at C = 330: the gap to 360 interpolates towards C0.
  expectSameDistribution(*readIesFile(fixture("bilateral.ies")), *readIesFile(fixture("bilateral_full.ies")));
}

TEST(PhotometryIes, Bilateral90To270FileExpandsLikeTheFullOne) {
  expectSameDistribution(*readIesFile(fixture("bilateral_90_270.ies")),
                         *readIesFile(fixture("bilateral_90_270_full.ies")));
}

TEST(PhotometryIes, CandelaIsContinuousAcrossTheZeroMeridian) {
  for (const char *name : {"bilateral_full.ies", "bilateral_90_270.ies", "quadrant.ies"}) {
    auto d = readIesFile(fixture(name));
    for (double gamma : {15.0, 50.0, 130.0}) {
      double below = d->candela(typeC(-1e-7, gamma)), above = d->candela(typeC(1e-7, gamma));
      EXPECT_NEAR(below, above, 1e-6 * d->maxCandela()) << name << " at γ " << gamma;
      EXPECT_NEAR(d->candela(typeC(360 - 1e-7, gamma)), above, 1e-6 * d->maxCandela()) << name;
    }
  }
}

TEST(PhotometryIes, CommasCrLfAndArbitraryWrappingReadTheSame) {
  expectSameDistribution(*readIesFile(fixture("wrapped_commas.ies")), *readIesFile(fixture("quadrant.ies")));
}

// ---- Types B and A ---------------------------------------------------------------

TEST(PhotometryIes, TypeBFloodlightBeamIsAlongLocalZ) {
  // I(H, V) = 1000 exp(−(H² + V²)/(2·15²)), given for H, V in 0…90 (symmetric).
  auto d = readIesFile(fixture("floodlight_type_b.ies"));
  EXPECT_EQ(d->type(), PhotometricType::B);
  auto beam = [](double h, double v) { return 1000 * std::exp(-(h * h + v * v) / (2 * 15 * 15)); };
  EXPECT_NEAR(d->candela({0, 0, 1}), 1000, 1e-6);
  EXPECT_NEAR(d->maxCandela(), 1000, 1e-6);
  for (double h : {-20.0, -5.0, 10.0, 35.0})
    for (double v : {-30.0, 0.0, 15.0, 25.0})
      EXPECT_NEAR(d->candela(typeB(h, v)), beam(h, v), 1e-5) << "H " << h << " V " << v;
  EXPECT_EQ(d->candela({0, 0, -1}), 0);  // behind the floodlight
  EXPECT_EQ(d->candela(normalize({0.2, 0.1, -1})), 0);
  // V turns about the y axis towards +x, H leaves the x–z plane towards +y.
  EXPECT_NEAR(d->candela(normalize({std::tan(radians(10)), 0, 1})), beam(0, 10), 1e-5);
  EXPECT_NEAR(d->candela({0, std::sin(radians(10)), std::cos(radians(10))}), beam(10, 0), 1e-5);
}

TEST(PhotometryIes, TypeBAndTypeAAnglesMapToTheDocumentedFrame) {
  // The beam's peak is at H = 20°, V = 10°: both types put it at their own
  // (H, V) direction.
  auto b = readIesFile(fixture("floodlight_type_b_asymmetric.ies"));
  EXPECT_NEAR(b->candela(typeB(20, 10)), 1000, 1e-6);
  EXPECT_NEAR(b->maxCandela(), 1000, 1e-6);
  EXPECT_NEAR(b->candela(typeB(-30, 40)), 1000 * std::exp(-(50.0 * 50 + 30 * 30) / 450), 1e-6);

  ScratchFolder scratch;
  std::string text = readText(fixture("floodlight_type_b_asymmetric.ies"));
  size_t at = text.find("1 -1 1 19 19 2 2");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 16, "1 -1 1 19 19 3 2");
  auto a = readIesFile(scratch.write("type_a.ies", text));
  EXPECT_EQ(a->type(), PhotometricType::A);
  EXPECT_NEAR(a->candela(typeA(20, 10)), 1000, 1e-6);
  EXPECT_NEAR(a->candela(typeA(-30, 40)), 1000 * std::exp(-(50.0 * 50 + 30 * 30) / 450), 1e-6);
  // Off the two principal planes the frames differ (type A's planes share the x axis, type B's the y axis).
  EXPECT_GT(std::abs(a->candela(typeB(40, 40)) - b->candela(typeB(40, 40))), 10.0);
}

// ---- Multipliers, tilt, versions -------------------------------------------------

TEST(PhotometryIes, MultiplierBallastFactorAndVersionFields) {
  // 1995: 500 × multiplier 2 × ballast 0.5 × ballast-lamp factor 0.9.
  EXPECT_NEAR(readIesFile(fixture("multipliers_1995.ies"))->candela({1, 0, 0}), 450, 1e-9);
  // 2002: the third field is "future use" and multiplies nothing.
  EXPECT_NEAR(readIesFile(fixture("multipliers_2002.ies"))->candela({1, 0, 0}), 500, 1e-9);
  // 2019: the third field is the file generation type (1.10000).
  auto lm2019 = readIesFile(fixture("generation_2019.ies"));
  EXPECT_NEAR(lm2019->candela({0, 1, 0}), 1000, 1e-9);
  EXPECT_NE(lm2019->description().find("Isotropic 2019"), std::string::npos);
  // 1991 (IESNA91): ballast factor 0.8.
  EXPECT_NEAR(readIesFile(fixture("iesna91.ies"))->candela({0, 0, 1}), 800, 1e-9);
  // 1986: no version line, labels instead of keywords.
  auto lm1986 = readIesFile(fixture("lm63_1986.ies"));
  EXPECT_NEAR(lm1986->candela({0, 0, -1}), 1000, 1e-9);
  EXPECT_NE(lm1986->description().find("1986"), std::string::npos) << lm1986->description();
}

TEST(PhotometryIes, TiltIncludedAndInAFileBeside) {
  auto included = readIesFile(fixture("tilt_include.ies"));
  EXPECT_NEAR(included->tiltFactor(0), 1, 1e-12);
  EXPECT_NEAR(included->tiltFactor(22.5), 0.95, 1e-12);
  EXPECT_NEAR(included->tiltFactor(90), 0.8, 1e-12);
  EXPECT_NEAR(included->tiltFactor(120), 0.8, 1e-12);     // held beyond the table
  EXPECT_NEAR(included->candela({0, 0, 1}), 1000, 1e-9);  // candela() leaves the tilt out

  auto beside = readIesFile(fixture("tilt_file.ies"));
  EXPECT_NEAR(beside->tiltFactor(45), 0.9, 1e-12);
  EXPECT_NEAR(beside->tiltFactor(90), 0.7, 1e-12);
  EXPECT_NEAR(beside->lumens(), 4 * kPi * 1000, 1e-6);
}

// ---- EULUMDAT ---------------------------------------------------------------------

TEST(PhotometryEulumdat, SameLuminaireAsTheIesFile) {
  auto ldt = readEulumdatFile(fixture("same_luminaire.ldt"));
  auto ies = readIesFile(fixture("same_luminaire.ies"));
  expectSameDistribution(*ldt, *ies, 1e-6);
  EXPECT_NE(ldt->description().find("Test luminaire same_luminaire.ldt"), std::string::npos) << ldt->description();
}

TEST(PhotometryEulumdat, EverySymmetryIndicatorExpandsLikeTheIesFile) {
  // Isym 4 with two lamp sets (1500 + 500 lm); Isym 3 with conversion factor 0.5;
  // Isym 0 ending at C330; Isym 1 with a negative lamp count (absolute photometry).
  expectSameDistribution(*readEulumdatFile(fixture("quadrant.ldt")), *readIesFile(fixture("quadrant.ies")), 1e-6);
  expectSameDistribution(*readEulumdatFile(fixture("bilateral_90_270.ldt")),
                         *readIesFile(fixture("bilateral_90_270.ies")), 1e-6);
  expectSameDistribution(*readEulumdatFile(fixture("full.ldt")), *readIesFile(fixture("bilateral_full.ies")), 1e-6);
  expectSameDistribution(*readEulumdatFile(fixture("isotropic.ldt")), *readIesFile(fixture("isotropic.ies")), 1e-9);
}

TEST(PhotometryFile, DispatchesOnTheExtension) {
  EXPECT_EQ(readPhotometricFile(fixture("isotropic.ldt"))->lumens(),
            readEulumdatFile(fixture("isotropic.ldt"))->lumens());
  ScratchFolder scratch;
  std::string upper = scratch.write("ISOTROPIC.IES", readText(fixture("isotropic.ies")));
  EXPECT_NEAR(readPhotometricFile(upper)->candela({0, 0, 1}), 1000, 1e-9);
  try {
    readPhotometricFile(scratch.write("lamp.txt", "hello"));
    FAIL() << "a .txt file was read";
  } catch (const InputError &e) {
    EXPECT_NE(e.message().find(".ies"), std::string::npos) << e.what();
    EXPECT_NE(e.message().find(".ldt"), std::string::npos) << e.what();
  }
}

// ---- Sampling ------------------------------------------------------------------------

using test::kPhiBins;
using test::kThetaBins;
using test::sphereBin;

void expectSamplingFollowsPdf(const PhotometricDistribution &d) {
  constexpr int kSamples = 200000, kSub = 8;
  std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(kThetaBins * kPhiBins, 0.0);
  Pcg32 rng(2026, 12);
  double sum = 0, sumSquares = 0;
  for (int k = 0; k < kSamples; ++k) {
    double pdf;
    Vec3 w = d.sample(rng.next(), rng.next(), pdf);
    ASSERT_NEAR(length(w), 1, 1e-9);
    ASSERT_GT(pdf, 0);
    ASSERT_NEAR(pdf, d.pdf(w), 1e-9 * pdf) << "sample() and pdf() disagree";
    observed[sphereBin(w)] += 1;
    double estimate = d.candela(w) / pdf;
    sum += estimate;
    sumSquares += estimate * estimate;
  }
  // ∫ pdf over each bin by the midpoint rule on a sub-grid.
  const double dz = 2.0 / (kThetaBins * kSub), dphi = 2 * kPi / (kPhiBins * kSub);
  double total = 0;
  for (int a = 0; a < kThetaBins * kSub; ++a) {
    double z = -1 + (a + 0.5) * dz, r = std::sqrt(std::max(0.0, 1 - z * z));
    for (int b = 0; b < kPhiBins * kSub; ++b) {
      double phi = (b + 0.5) * dphi, p = d.pdf({r * std::cos(phi), r * std::sin(phi), z}) * dz * dphi;
      expected[(a / kSub) * kPhiBins + b / kSub] += p * kSamples;
      total += p;
    }
  }
  EXPECT_NEAR(total, 1, 0.01) << "∫ pdf dω";
  test::ChiSquareResult r = test::chiSquare(observed, expected);
  EXPECT_GT(r.pValue, test::significanceLevel(kChiSquareTestsInThisFile))
      << d.file() << ": chi² = " << r.statistic << " with " << r.degreesOfFreedom << " degrees of freedom";
  // E[candela/pdf] = lumens, within five standard errors.
  double mean = sum / kSamples, variance = std::max(0.0, sumSquares / kSamples - mean * mean);
  EXPECT_NEAR(mean, d.lumens(), 5 * std::sqrt(variance / kSamples) + 1e-9 * d.lumens()) << d.file();
}

TEST(PhotometrySampling, TypeCSamplesFollowThePdf) {
  expectSamplingFollowsPdf(*readIesFile(fixture("bilateral_90_270.ies")));
}

TEST(PhotometrySampling, HemisphericalTypeCSamplesFollowThePdf) {
  expectSamplingFollowsPdf(*readEulumdatFile(fixture("quadrant.ldt")));
  auto lambert = readIesFile(fixture("lambertian_downlight.ies"));
  EXPECT_EQ(lambert->pdf({0, 0, -1}), 0);  // nothing above the horizontal
  EXPECT_GT(lambert->pdf(typeC(10, 80)), 0);
}

TEST(PhotometrySampling, TypeBSamplesFollowThePdf) {
  auto d = readIesFile(fixture("floodlight_type_b_asymmetric.ies"));
  expectSamplingFollowsPdf(*d);
  EXPECT_EQ(d->pdf({0, 0, -1}), 0);
}

TEST(PhotometrySampling, PdfIsPositiveWhereverCandelaIs) {
  for (const char *name : {"bilateral_90_270.ies", "lambertian_downlight.ies", "floodlight_type_b.ies"}) {
    auto d = readIesFile(fixture(name));
    for (const Vec3 &w : testDirections(5000))
      if (d->candela(w) > 0) {
        ASSERT_GT(d->pdf(w), 0) << name << " at (" << w.x << ", " << w.y << ", " << w.z << ")";
      }
  }
}

// ---- Malformed files -----------------------------------------------------------------

const char *kHeader =
    "IESNA:LM-63-2002\n"  // 1
    "[TEST] malformed\n"  // 2
    "[MANUFAC] Radiant\n";

/// Reads `text` as `name`; expects an InputError naming the file, `line` and `phrase`.
void expectRefused(const std::string &name, const std::string &text, int line, const std::string &phrase) {
  ScratchFolder scratch;
  std::string path = scratch.write(name, text);
  try {
    readPhotometricFile(path);
    ADD_FAILURE() << name << " was read";
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().file, path) << e.what();
    EXPECT_EQ(e.location().line, line) << e.what();
    EXPECT_NE(e.message().find(phrase), std::string::npos) << "'" << phrase << "' not in: " << e.what();
  }
}

TEST(PhotometryErrors, IesFilesAreRefusedWithFileLineAndWhatWasExpected) {
  const std::string h = kHeader;  // lines 1–3
  const std::string ok = "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n1000 1000 1000\n";
  expectRefused("good.ies", h + ok + "5\n", 10, "expected the end of the file");
  expectRefused("no_tilt.ies", h + "1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n1000 1000 1000\n", 8, "TILT=");
  expectRefused("bad_tilt.ies", h + "TILT NONE\n1 -1 1 3 1 1 2 0 0 0\n", 5, "before its TILT= line");
  expectRefused("unknown_version.ies", "IESNA:LM-63-2030\nTILT=NONE\n", 1, "IESNA:LM-63-2002");
  expectRefused("fewer.ies", h + "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n1000 1000\n", 9,
                "candela value 3 of 3");
  expectRefused("decreasing.ies", h + "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90\n80\n0\n1 1 1\n", 8,
                "vertical angle 3 of 3 is 80, not greater");
  expectRefused("negative.ies", h + "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n1000 -1 1000\n", 9,
                "candela value 2 of 3 is negative");
  expectRefused("nan.ies", h + "TILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n1000 nan 1000\n", 9,
                "found 'nan'");
  expectRefused("overflow.ies", h + "TILT=NONE\n1 -1 1e300 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n1000 1e300 1000\n", 9,
                "more than 1e18");
  expectRefused("hex.ies", h + "TILT=NONE\n1 -1 0x1p1 3 1 1 2 0 0 0\n", 5, "candela multiplier");
  expectRefused("truncated.ies", h + "TILT=NONE\n1 -1 1 3 1 1 2 0 0", 5, "the luminous opening's height");
  expectRefused("huge.ies", h + "TILT=NONE\n1 -1 1 1000000000 1 1 2 0 0 0\n", 5, "expected 1 to 10000");
  expectRefused("huge_product.ies", h + "TILT=NONE\n1 -1 1 10000 10000 1 2 0 0 0\n", 5, "at most 1000000");
  expectRefused("type.ies", h + "TILT=NONE\n1 -1 1 3 1 4 2 0 0 0\n", 5, "expected 1 (C), 2 (B) or 3 (A)");
  expectRefused("units.ies", h + "TILT=NONE\n1 -1 1 3 1 1 3 0 0 0\n", 5, "expected 1 (feet) or 2 (metres)");
  expectRefused("quadrant_45.ies", h + "TILT=NONE\n1 -1 1 2 2 1 2 0 0 0\n1 1 10\n0 90\n0\n45\n1 1 1 1\n", 8,
                "expected 0 alone");
  expectRefused("hair_apart.ies",
                h + "TILT=NONE\n1 -1 1 2 3 1 2 0 0 0\n1 1 10\n0 90\n0 90.0000001 90.0000005\n1 1 1 1 1 1\n", 8,
                "closer together");
  expectRefused("one_vertical.ies", h + "TILT=NONE\n1 -1 1 1 1 1 2 0 0 0\n1 1 10\n0\n0\n1\n", 7,
                "at least two vertical angles");
  expectRefused("type_b_range.ies", h + "TILT=NONE\n1 -1 1 2 2 2 2 0 0 0\n1 1 10\n0 90\n10 90\n1 1 1 1\n", 8,
                "start at -90 or at 0");
  expectRefused("tilt_geometry.ies", h + "TILT=INCLUDE\n4\n", 5, "expected 1, 2 or 3");
  expectRefused("tilt_count.ies", h + "TILT=INCLUDE\n1\n2\n0 90\n1\n", 8, "tilt factor 2 of 2");
  expectRefused("tilt_missing.ies", h + "TILT=no_such_file.tlt\n" + ok.substr(10), 4, "cannot open IES tilt file");
  expectRefused("empty.ies", "", 1, "empty");
}

TEST(PhotometryErrors, TiltFileErrorsNameTheTiltFile) {
  ScratchFolder scratch;
  std::string tilt = scratch.write("bad.tlt", "1\n2\n0 90\n1 -0.5\n");
  std::string ies = scratch.write("uses_bad_tilt.ies", std::string(kHeader) +
                                                           "TILT=bad.tlt\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n"
                                                           "1000 1000 1000\n");
  try {
    readIesFile(ies);
    FAIL() << "read";
  } catch (const InputError &e) {
    EXPECT_EQ(e.location().file, tilt) << e.what();
    EXPECT_EQ(e.location().line, 4) << e.what();
    EXPECT_NE(e.message().find("tilt factor 2 of 2 is negative"), std::string::npos) << e.what();
  }
}

TEST(PhotometryErrors, FilesOver64MiBAreRefusedUnread) {
  ScratchFolder scratch;
  std::string path = scratch.write("huge.ies", "IESNA:LM-63-2002\n");
  fs::resize_file(path, (uintmax_t(64) << 20) + 1);  // sparse: nothing is written
  try {
    readIesFile(path);
    FAIL() << "read";
  } catch (const InputError &e) {
    EXPECT_NE(e.message().find("64 MiB"), std::string::npos) << e.what();
  }
}

/// The lines of a good EULUMDAT file, to break one at a time.
std::vector<std::string> eulumdatLines() {
  std::vector<std::string> lines;
  std::istringstream in(readText(fixture("quadrant.ldt")));
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::string joinLines(const std::vector<std::string> &lines, size_t count = SIZE_MAX) {
  std::string text;
  for (size_t i = 0; i < lines.size() && i < count; ++i) text += lines[i] + "\n";
  return text;
}

TEST(PhotometryErrors, EulumdatFilesAreRefusedWithLineAndField) {
  auto lines = eulumdatLines();
  auto with = [&](size_t line, const std::string &text) {
    auto changed = lines;
    changed[line - 1] = text;
    return joinLines(changed);
  };
  expectRefused("isym.ldt", with(3, "7"), 3, "line 3, the symmetry indicator Isym, is 7: expected 0 to 4");
  expectRefused("mc.ldt", with(4, "1000000000"), 4, "the number Mc of C planes");
  expectRefused("mc_odd.ldt", with(4, "10"), 4, "expects a multiple of 4");
  expectRefused("ng.ldt", with(6, "abc"), 6, "line 6, the number Ng of intensities per C plane: expected an integer");
  expectRefused("conversion.ldt", with(24, "0"), 24, "conversion factor");
  expectRefused("flux.ldt", with(29, "-5"), 29, "the total luminous flux of lamp set 1");
  expectRefused("truncated_header.ldt", joinLines(lines, 20), 20, "expected line 21");
  expectRefused("truncated_values.ldt", joinLines(lines, lines.size() - 3), static_cast<int>(lines.size()) - 3,
                "the file ends where intensity");
  expectRefused("extra.ldt", joinLines(lines) + "1\n", static_cast<int>(lines.size()) + 1,
                "expected the end of the file");
  // The C angles of the stored planes of Isym 4 must run from 0 to 90.
  size_t firstCAngle = 26 + 12 + 10 + 1;  // 26 header lines, two lamp sets, 10 direct ratios
  ASSERT_EQ(lines[firstCAngle - 1], "0");
  expectRefused("c_angles.ldt", with(firstCAngle, "5"), static_cast<int>(firstCAngle), "Isym 4 stores the planes");
  expectRefused("c_decreasing.ldt", with(firstCAngle + 2, "20"), static_cast<int>(firstCAngle) + 2,
                "C angle 3 of 12 is 20, not greater");
}

}  // namespace
}  // namespace radiant
