// The fuzz targets' inputs as regression tests (docs/fuzzing.md): every file
// of fuzz/corpus/<target>/ (the seeds) and tests/fuzz-regressions/<target>/
// (inputs that once crashed, hung or ran out of memory, kept after their fix)
// is fed through the same feed as the fuzz target (fuzz/fuzz_inputs.h), and
// must be accepted or refused with an InputError that names the file. Any
// other exception fails here; a crash or a sanitizer report fails the run
// (CI runs this under ASan and UBSan too).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz_inputs.h"
#include "io/image.h"
#include "sanitizer.h"
#include "util/error.h"

namespace radiant {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> filesIn(const fs::path &folder) {
  std::vector<fs::path> files;
  std::error_code error;
  if (!fs::is_directory(folder, error)) return files;
  for (const fs::directory_entry &entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().filename() != "README.md") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzRegressions : public testing::TestWithParam<fuzz::FuzzTarget> {};

/// Feeds one input; returns whether it was accepted, fails the test on anything but an InputError naming a file.
bool acceptedOrRefused(const fuzz::FuzzTarget &target, const fs::path &file, const fuzz::ScratchFolder &folder) {
  SCOPED_TRACE(file.string());
  const std::vector<uint8_t> input = fuzz::readFileBytes(file.string());
  try {
    target.feed(input, folder.path());
    return true;
  } catch (const InputError &e) {
    // The message must lead the user to the file at fault: one the feed
    // wrote (the input, or a file it names in the scratch folder).
    EXPECT_NE(std::string(e.what()).find(folder.path()), std::string::npos) << e.what();
  } catch (const std::exception &e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
  }
  return false;
}

// The seeds are valid files of their format (docs/fuzzing.md): each one must
// load, or the feed has drifted from the program (a fixture missing, the
// solution's fingerprint not patched) and the fuzzer starts from nothing.
TEST_P(FuzzRegressions, EverySeedIsAccepted) {
  const fuzz::FuzzTarget &target = GetParam();
  const std::vector<fs::path> seeds = filesIn(fs::path(RADIANT_SOURCE_DIR) / "fuzz" / "corpus" / target.name);
  ASSERT_FALSE(seeds.empty()) << "no seed corpus in fuzz/corpus/" << target.name;
  const fuzz::ScratchFolder folder(std::string("test-") + target.name);
  for (const fs::path &seed : seeds) EXPECT_TRUE(acceptedOrRefused(target, seed, folder)) << seed << " was refused";
}

TEST_P(FuzzRegressions, EverySavedInputIsAcceptedOrRefusedWithAnInputError) {
  const fuzz::FuzzTarget &target = GetParam();
  const fuzz::ScratchFolder folder(std::string("test-") + target.name);
  for (const fs::path &input : filesIn(fs::path(RADIANT_SOURCE_DIR) / "tests" / "fuzz-regressions" / target.name))
    acceptedOrRefused(target, input, folder);
}

// The inputs left in fuzz/findings/ (docs/fuzzing.md): undefined behaviour
// inside Debian's stb_image 2.27 (a shift of 32 or more in its JPEG bit
// reader, memcpy from a null pointer on a zero-length PNG IDAT), which
// UBSan reports in code Radiant does not own, and JPEGs whose headers claim
// 13–16 M texels (2.4 s each to refuse); and two MGF files of spheres in
// nested arrays (2–4 s and up to 1 GB to refuse in Release, one at the limit
// of 2²³ vertices; minutes instrumented). The Release build still feeds them,
// so that a crash or a hang of ours shows; the sanitizer build skips them.
TEST(FuzzRegressions, TheThirdPartyFindingsAreAcceptedOrRefusedInRelease) {
#if RADIANT_UNDER_SANITIZER
  GTEST_SKIP() << "undefined behaviour inside stb_image 2.27 (Debian's), reported by UBSan, and slow inputs: "
                  "Release only";
#endif
  for (const fuzz::FuzzTarget &target : fuzz::fuzzTargets()) {
    const fuzz::ScratchFolder folder(std::string("findings-") + target.name);
    for (const fs::path &input : filesIn(fs::path(RADIANT_SOURCE_DIR) / "fuzz" / "findings" / target.name))
      acceptedOrRefused(target, input, folder);
  }
}

/// The process's peak resident memory so far, bytes (Linux: ru_maxrss in KiB).
double peakResidentBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024;
}

// No huge allocation for bad input: a 500-byte OpenEXR file whose header
// claims 313 345 × 513 pixels (within readImage's limit of 2^28) made readExr
// allocate the whole image, 1.9 GB, before OpenEXR found the pixels missing.
// Read in strips, it fails at the first one. The peak resident memory must
// not grow by more than 256 MB (the vector was value-initialised, so every
// page of it was touched and counted); it fails with the old reader.
TEST(FuzzRegressions, AnExrClaimingMorePixelsThanItHoldsAllocatesLittle) {
  const std::string file =
      std::string(RADIANT_SOURCE_DIR) + "/tests/fuzz-regressions/image/oom-exr-claims-313345x513-within-pixel-limit";
  const double before = peakResidentBytes();
  const fuzz::ScratchFolder folder("test-exr-strips");
  const std::string exr = folder.path() + "/claims-160M-pixels.exr";
  fs::copy_file(file, exr, fs::copy_options::overwrite_existing);
  EXPECT_THROW(readImage(exr), InputError);
  EXPECT_LT(peakResidentBytes() - before, 256.0 * (1 << 20)) << "bytes more at the peak";
}

INSTANTIATE_TEST_SUITE_P(Targets, FuzzRegressions,
                         testing::ValuesIn(fuzz::fuzzTargets().begin(), fuzz::fuzzTargets().end()),
                         [](const testing::TestParamInfo<fuzz::FuzzTarget> &info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace radiant
