// Input files are read only when they are regular files (util/input_file.h):
// a FIFO named where a file is expected — a glTF buffer, an MGF include, an
// MTL, a scene, a photometric file, a texture, an image, a solution — is
// refused with "… is not a regular file", at once. Before, the readers opened
// it by name and blocked in open() or read() until a writer came (issue 38).

#include "util/input_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <string>

#include "io/image.h"
#include "io/solution_file.h"
#include "scene/load_scene.h"
#include "scene/photometry.h"
#include "temp_dir.h"
#include "texture/texture.h"

namespace radiant {
namespace {

namespace fs = std::filesystem;

using test::TempDir;

/// Runs `read`, which must refuse `fifo` with an error holding `expected`.
/// A reader that blocks on the FIFO is released after 10 s (a writer opens
/// and closes it, so the read sees an end of file) and the test fails,
/// rather than hanging the suite.
void expectRefusedWithoutBlocking(const std::string &fifo, const std::function<void()> &read,
                                  const std::string &expected) {
  auto outcome = std::async(std::launch::async, [&]() -> std::string {
    try {
      read();
      return "(read without an error)";
    } catch (const std::exception &e) {
      return e.what();
    }
  });
  if (outcome.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    ADD_FAILURE() << "blocked for 10 s on the FIFO " << fifo;
    while (outcome.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
      const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // succeeds once the reader waits in open
      if (writer >= 0) ::close(writer);
    }
  }
  const std::string message = outcome.get();
  EXPECT_NE(message.find(expected), std::string::npos) << message;
}

constexpr const char *kNotRegular = "is not a regular file (it is a FIFO)";

TEST(InputFile, ReadsRegularFilesAndNamesWhatElseItWasGiven) {
  TempDir dir("input-file");
  const std::string text = dir.write("a.txt", "hello");
  InputFileRead read = tryReadInputFile(text);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(read.bytes, "hello");
  EXPECT_EQ(tryReadInputFile(dir.file("absent")).status, InputFileRead::Status::Missing);
  read = tryReadInputFile(dir.file(""));
  EXPECT_EQ(read.status, InputFileRead::Status::NotRegular);
  EXPECT_EQ(read.kind, "a directory");
  if (fs::exists("/dev/zero")) {  // endless: read to the bound, it would exhaust memory
    read = tryReadInputFile("/dev/zero");
    EXPECT_EQ(read.status, InputFileRead::Status::NotRegular);
    EXPECT_EQ(read.kind, "a character device");
  }
  read = tryReadInputFile(text, 4);
  EXPECT_EQ(read.status, InputFileRead::Status::TooLarge);
  EXPECT_EQ(inputFileProblem(read, "note 'a.txt'", 4), "note 'a.txt' is larger than 4 bytes (it has 5 bytes)");
  EXPECT_EQ(readInputFilePrefix(text, 4), "hell");
  const std::string fifo = dir.fifo("pipe");
  EXPECT_EQ(readInputFilePrefix(fifo, 4), "");
  expectRefusedWithoutBlocking(
      fifo, [&] { readInputFile(fifo, InputLocation{"scene.json"}, "thing"); },
      "scene.json: thing '" + fifo + "' " + kNotRegular);
}

TEST(InputFile, AGltfBufferThatIsAFifoIsRefusedAtItsUri) {
  TempDir dir("input-file");
  const std::string fifo = dir.fifo("buffer.bin");
  const std::string gltf = dir.write("model.gltf", R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "buffer.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})");
  expectRefusedWithoutBlocking(
      fifo, [&] { loadScene(gltf); }, "at /buffers/0/uri: buffer file '");
  expectRefusedWithoutBlocking(
      fifo, [&] { loadScene(gltf); }, kNotRegular);
}

TEST(InputFile, AnMgfIncludeThatIsAFifoIsRefusedAtItsLine) {
  TempDir dir("input-file");
  const std::string fifo = dir.fifo("part.mgf");
  const std::string mgf = dir.write("room.mgf", "# a room\ni part.mgf\n");
  expectRefusedWithoutBlocking(
      fifo, [&] { loadScene(mgf); }, "room.mgf:2: MGF file '" + fifo + "' " + kNotRegular);
}

TEST(InputFile, ObjMtlAndTexturesThatAreFifosAreRefused) {
  TempDir dir("input-file");
  const std::string mtl = dir.fifo("pipe.mtl");
  const std::string obj = dir.write("box.obj", "mtllib pipe.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectRefusedWithoutBlocking(
      mtl, [&] { loadScene(obj); }, "box.obj:1: material library '" + mtl + "' " + kNotRegular);

  const std::string texture = dir.fifo("pipe.png");
  dir.write("textured.mtl", "newmtl m\nKd 0.5 0.5 0.5\nmap_Kd pipe.png\n");
  const std::string textured =
      dir.write("textured.obj", "mtllib textured.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl m\nf 1/1 2/1 3/1\n");
  expectRefusedWithoutBlocking(
      texture, [&] { loadScene(textured); }, "named by map_Kd " + std::string(kNotRegular));
  expectRefusedWithoutBlocking(
      texture, [&] { Texture::load(texture, TextureEncoding::Colour); }, kNotRegular);

  const std::string bareObj = dir.fifo("bare.obj");
  expectRefusedWithoutBlocking(
      bareObj, [&] { loadScene(bareObj); }, "OBJ file '" + bareObj + "' " + kNotRegular);
}

TEST(InputFile, SceneFilesThatAreFifosAreRefused) {
  TempDir dir("input-file");
  for (const char *name : {"scene.json", "model.gltf", "model.glb", "room.mgf", "no-extension"}) {
    const std::string fifo = dir.fifo(name);
    expectRefusedWithoutBlocking(
        fifo, [&] { loadScene(fifo); }, kNotRegular);
  }
}

TEST(InputFile, PhotometryImagesAndSolutionsThatAreFifosAreRefused) {
  TempDir dir("input-file");
  const std::string ies = dir.fifo("lamp.ies"), ldt = dir.fifo("lamp.ldt");
  expectRefusedWithoutBlocking(
      ies, [&] { readIesFile(ies); }, kNotRegular);
  expectRefusedWithoutBlocking(
      ldt, [&] { readEulumdatFile(ldt); }, kNotRegular);
  const std::string scene = dir.write("lit.json", R"({"version": 1, "materials": {"grey": {"reflectance": 0.5}},
    "objects": [{"type": "quad", "material": "grey", "vertices": [[-1, 0, -1], [-1, 0, 1], [1, 0, 1], [1, 0, -1]]}],
    "luminaires": [{"ies": "lamp.ies", "position": [0, 1, 0]}]})");
  expectRefusedWithoutBlocking(
      ies, [&] { loadScene(scene); }, kNotRegular);
  for (const char *name : {"image.exr", "image.pfm", "image.hdr"}) {
    const std::string fifo = dir.fifo(name);
    expectRefusedWithoutBlocking(
        fifo, [&] { readImage(fifo); }, kNotRegular);
  }
  const std::string solution = dir.fifo("solution.sol");
  expectRefusedWithoutBlocking(
      solution, [&] { readSolutionPasses(solution, Scene{}); }, kNotRegular);
}

}  // namespace
}  // namespace radiant
