// Loaders whose cost grows linearly with the items of a file (issue 38): an
// OBJ of 10⁵ usemtl materials and a scene of 10⁵ luminaires were quadratic,
// each name looked up by scanning every name. Here the lookups are counted
// (detail::NameIndex), and the loaders checked on a few thousand items for
// what they build; bench/input_scale.sh times 10⁴–10⁵ (docs/PERFORMANCE.md).

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "scene/load_detail.h"
#include "scene/load_scene.h"
#include "temp_dir.h"

namespace radiant {
namespace {

using test::TempDir;

TEST(InputScale, NameLookupsHashEachNameOnceHoweverManyLookups) {
  constexpr int kMaterials = 20000;
  std::vector<Material> materials;
  detail::MaterialNames names(materials);
  for (int i = 0; i < kMaterials; ++i) {
    Material m;
    m.name = fmt::format("m{}", i);
    materials.push_back(m);
    // A lookup per added item, as a loader naming each new material makes:
    // a scan would compare i names here, 2·10⁸ in all.
    ASSERT_EQ(names.find(m.name), i);
    ASSERT_EQ(names.find("absent"), -1);
  }
  EXPECT_EQ(names.namesHashed(), size_t(kMaterials));
  for (int i = 0; i < kMaterials; i += 7) EXPECT_EQ(names.find(fmt::format("m{}", i)), i);
  EXPECT_EQ(names.namesHashed(), size_t(kMaterials));
  materials.push_back(materials.front());  // a second "m0": the first wins, as with findMaterial
  EXPECT_EQ(names.find("m0"), 0);
  EXPECT_EQ(names.namesHashed(), size_t(kMaterials) + 1);
}

TEST(InputScale, AnObjOfThousandsOfMaterialsGivesEachFaceItsOwn) {
  constexpr int kMaterials = 3000;
  std::string obj = "mtllib many.mtl\n", mtl;
  for (int i = 0; i < kMaterials; ++i) {
    mtl += fmt::format("newmtl m{}\nKd 0.{} 0.5 0.5\n", i, 1 + i % 8);
    const int v = 3 * i;
    obj += fmt::format("v {} 0 0\nv {} 0 0\nv {} 0 1\nusemtl m{}\nf {} {} {}\n", i, i + 1, i, i, v + 1, v + 3, v + 2);
  }
  TempDir dir("input-scale");
  dir.write("many.mtl", mtl);
  const Scene scene = loadScene(dir.write("many.obj", obj));
  ASSERT_EQ(scene.faces.size(), size_t(kMaterials));
  std::set<uint32_t> used;
  for (size_t f = 0; f < scene.faces.size(); ++f) {
    const Material &m = scene.materials[scene.faces[f].material];
    // Faces keep the file's order; face f is the one after "usemtl mf".
    EXPECT_EQ(m.name, fmt::format("m{}", f));
    EXPECT_NEAR(m.diffuse[0], 0.1 * double(1 + f % 8), 1e-6) << m.name;
    used.insert(scene.faces[f].material);
  }
  EXPECT_EQ(used.size(), size_t(kMaterials));
}

TEST(InputScale, LuminairesOfOneFileShareItsDistributionAndKeepTheirNames) {
  constexpr int kLuminaires = 2000;
  std::string luminaires;
  for (int i = 0; i < kLuminaires; ++i)
    luminaires +=
        fmt::format(R"({}{{"ies": "{}/tests/photometry/lambertian_downlight.ies", "position": [{}, 2.5, {}]}})",
                    i ? ", " : "", RADIANT_SOURCE_DIR, i % 50, i / 50);
  const std::string scene = R"({"version": 1, "materials": {"grey": {"reflectance": 0.5}},
    "objects": [{"type": "quad", "material": "grey", "vertices": [[0, 0, 0], [0, 0, 50], [50, 0, 50], [50, 0, 0]]}],
    "lights": [{"type": "point", "name": "luminaire-7", "position": [1, 1, 1], "intensity": 1}],
    "luminaires": [)";
  // luminaire-7 is taken by the point light: the seventh luminaire's default name is a second one.
  try {
    parseSceneJson(scene + luminaires + "]}", "scene.json");
    ADD_FAILURE() << "a second light named luminaire-7 was accepted";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("at /luminaires/7: a second light named 'luminaire-7'"), std::string::npos)
        << e.what();
  }
  std::string renamed = scene;
  renamed.replace(renamed.find("luminaire-7"), 11, "desk-lamp");
  const Scene loaded = parseSceneJson(renamed + luminaires + "]}", "scene.json");
  ASSERT_EQ(loaded.lights.size(), size_t(kLuminaires) + 1);
  std::set<std::string> names;
  for (const PointLight &light : loaded.lights) names.insert(light.name);
  EXPECT_EQ(names.size(), loaded.lights.size());
  // One file, read and tabulated once for all its luminaires.
  for (size_t i = 2; i < loaded.lights.size(); ++i)
    EXPECT_EQ(loaded.lights[i].photometry.get(), loaded.lights[1].photometry.get());
}

TEST(InputScale, AnMgfFileIncludedThousandsOfTimesMakesItsMaterialOnce) {
  // Each include defines its material again with the same values: one
  // Radiant material for all, not one per include (each new one was named
  // grey#k after trying grey#2 … grey#k−1: 5 s for 10⁴ includes, minutes for
  // 10⁵; bench/input_scale.sh --cases includes).
  constexpr int kIncludes = 4000;
  TempDir dir("input-scale-mgf");
  dir.write("quad.mgf",
            "m grey =\n c\n rd 0.5\nv a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 0 1\n"
            "v d =\n p 0 0 1\nf a b c d\n");
  std::string main;
  for (int i = 0; i < kIncludes; ++i) main += fmt::format("i quad.mgf -t {} 0 {}\n", 2 * (i % 64), 2 * (i / 64));
  const Scene scene = loadScene(dir.write("many.mgf", main));
  ASSERT_EQ(scene.faces.size(), size_t(kIncludes));
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, "grey");
  EXPECT_NEAR(scene.materials[0].diffuse[0], 0.5, 1e-6);
}

TEST(InputScale, AnMgfMaterialChangedThousandsOfTimesNamesEachVersion) {
  // A material changed after faces used it is a new one per change, named
  // grey, grey#2, grey#3, …; a name the file took itself is skipped.
  constexpr int kVersions = 3000;
  std::string mgf = "m grey#3 =\n c\n rd 0.9\nv a =\n p 0 0 0\nv b =\n p 1 0 0\nv c =\n p 1 0 1\nf a b c\n";
  for (int i = 0; i < kVersions; ++i)
    mgf += fmt::format("m grey =\n c\n rd {}\nv a =\n p {} 0 0\nv b =\n p {} 0 0\nv c =\n p {} 0 1\nf a b c\n",
                       0.1 + 0.8 * i / kVersions, i, i + 1, i);
  TempDir dir("input-scale-mgf-versions");
  const Scene scene = loadScene(dir.write("versions.mgf", mgf));
  ASSERT_EQ(scene.materials.size(), size_t(kVersions) + 1);
  std::set<std::string> names;
  for (const Material &m : scene.materials) names.insert(m.name);
  EXPECT_EQ(names.size(), scene.materials.size()) << "every version has its own name";
  EXPECT_EQ(scene.materials[1].name, "grey");
  EXPECT_EQ(scene.materials[2].name, "grey#2");
  EXPECT_EQ(scene.materials[3].name, "grey#4") << "grey#3 is the file's own";
  EXPECT_NEAR(scene.materials[kVersions].diffuse[0], 0.1 + 0.8 * (kVersions - 1) / kVersions, 1e-6);
}

}  // namespace
}  // namespace radiant
