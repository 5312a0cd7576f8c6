// A photometric file is told by its content (photometricFormatOf): a
// EULUMDAT file given under "ies", or read as IES, is named for what it is
// rather than parsed as LM-63 and refused with "the file ends before its
// TILT= line" (issue 38); an IES file under "ldt" likewise.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include "input_errors.h"
#include "scene/load_scene.h"
#include "scene/photometry.h"

namespace radiant {
namespace {

namespace fs = std::filesystem;

const fs::path kPhotometry = fs::path(RADIANT_SOURCE_DIR) / "tests/photometry";

std::string readText(const fs::path &path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string sceneWithLuminaire(const std::string &key, const fs::path &file) {
  return R"({"version": 1, "materials": {"grey": {"reflectance": 0.5}},
    "objects": [{"type": "quad", "material": "grey", "vertices": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]}],
    "luminaires": [{")" +
         key + R"(": ")" + file.string() + R"(", "position": [0, 1, 0]}]})";
}

TEST(PhotometricFormat, EveryTestFileIsToldByItsContent) {
  size_t files = 0;
  for (const auto &entry : fs::directory_iterator(kPhotometry)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".ies" && extension != ".ldt") continue;
    ++files;
    EXPECT_EQ(photometricFormatOf(readText(entry.path())),
              extension == ".ies" ? PhotometricFormat::Ies : PhotometricFormat::Eulumdat)
        << entry.path();
  }
  EXPECT_GE(files, 10u);
  EXPECT_EQ(photometricFormatOf(""), PhotometricFormat::Unknown);
  EXPECT_EQ(photometricFormatOf("some text\nthat is\nneither\n1\n2\n3\n4\n"), PhotometricFormat::Unknown);
}

TEST(PhotometricFormat, AEulumdatFileUnderIesIsNamedAtItsJsonPath) {
  const fs::path ldt = kPhotometry / "full.ldt";
  const std::string error = test::inputErrorOf([&] { parseSceneJson(sceneWithLuminaire("ies", ldt), "scene.json"); });
  EXPECT_NE(error.find("scene.json: at /luminaires/0/ies: this is a EULUMDAT file: give it as \"ldt\""),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("full.ldt"), std::string::npos) << error;
  // Under its own key it reads.
  EXPECT_EQ(parseSceneJson(sceneWithLuminaire("ldt", ldt), "scene.json").lights.size(), 1u);
}

TEST(PhotometricFormat, AnIesFileUnderLdtIsNamedAtItsJsonPath) {
  const fs::path ies = kPhotometry / "lambertian_downlight.ies";
  const std::string error = test::inputErrorOf([&] { parseSceneJson(sceneWithLuminaire("ldt", ies), "scene.json"); });
  EXPECT_NE(error.find("scene.json: at /luminaires/0/ldt: this is an IES LM-63 file: give it as \"ies\""),
            std::string::npos)
      << error;
}

TEST(PhotometricFormat, TheReadersNameAFileOfTheOtherFormat) {
  // A EULUMDAT file named .ies (the case the issue found), read by extension.
  const fs::path renamed = fs::temp_directory_path() / ("radiant-ldt-as-ies-" + std::to_string(::getpid()) + ".ies");
  fs::copy_file(kPhotometry / "full.ldt", renamed, fs::copy_options::overwrite_existing);
  const std::string error = test::inputErrorOf([&] { readPhotometricFile(renamed.string()); });
  fs::remove(renamed);
  EXPECT_NE(error.find(":1: this is a EULUMDAT file, not an IES LM-63 file"), std::string::npos) << error;
  EXPECT_EQ(error.find("TILT= line\n"), std::string::npos) << error;
  const std::string other =
      test::inputErrorOf([&] { readEulumdatFile((kPhotometry / "lambertian_downlight.ies").string()); });
  EXPECT_NE(other.find(":1: this is an IES LM-63 file, not a EULUMDAT file"), std::string::npos) << other;
}

}  // namespace
}  // namespace radiant
