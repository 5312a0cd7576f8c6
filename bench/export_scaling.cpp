// radiant export's cost per element (docs/PERFORMANCE.md "Export"): baking the
// solution into triangles (radiosity mesh → vertices with light) and writing
// the .glb, and the file's size, over meshes of 10³ to 10⁶ elements of the
// Cornell box. The light values do not change the cost: the solution is the
// mesh's initial one (emission only), not solved, so a million elements take
// seconds, not the minutes of a solve.
//
//   build/export_scaling [scene.json] [--repeats 3]     (from the repository root)
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>

#include "bench_common.h"
#include "export/baked_mesh.h"
#include "export/gltf_writer.h"
#include "mesh/mesh.h"
#include "radiosity/solution.h"
#include "scene/load_scene.h"

using namespace radiant;

int main(int argc, char **argv) {
  std::string scenePath = "scenes/cornell-box/scene.json";
  double repeats = 3;
  if (!bench::parseSceneAndNumber(argc, argv, "--repeats", "N", scenePath, repeats)) return 2;
  const Scene scene = loadScene(scenePath);
  const std::string path = (std::filesystem::temp_directory_path() / "radiant-export-scaling.glb").string();
  fmt::print("export of {} (load {:.2f}), medians of {:g} runs\n", scenePath, bench::loadAverage(), repeats);
  fmt::print("{:>9} {:>10} {:>10} {:>8} {:>8} {:>11} {:>11}\n", "elements", "triangles", "vertices", "bake s",
             "write s", "µs/element", "bytes/elem");
  // Element edges (metres) giving about 10³, 10⁴, 10⁵ and 10⁶ elements of the box's 5.5 m² of surface.
  for (double edge : {0.075, 0.024, 0.0075, 0.0024}) {
    MeshOptions options;
    options.maxEdgeLength = edge;
    Solution solution = initialSolution(scene, buildMesh(scene, options));
    for (size_t e = 0; e < solution.elementCount(); ++e) solution.radiosity[e] = solution.emission[e];
    solution.updateNodesAndErrors();
    std::vector<double> bake, write;
    BakedMesh baked;
    for (int r = 0; r < int(repeats); ++r) {
      auto start = std::chrono::steady_clock::now();
      baked = bakeSolution(scene, solution, [](const float l[3], double d[3]) {
        for (int c = 0; c < 3; ++c) d[c] = std::min(1.0, double(l[c]));
      });
      bake.push_back(bench::secondsSince(start));
      start = std::chrono::steady_clock::now();
      writeGltf(scene, baked, ExportProvenance{"none", "linear", {}, ""}, path);
      write.push_back(bench::secondsSince(start));
    }
    size_t triangles = 0, vertices = 0;
    for (const BakedPrimitive &p : baked.primitives) triangles += p.triangleCount(), vertices += p.vertexCount();
    const double elements = double(baked.elements);
    const double bytes = double(std::filesystem::file_size(path));
    const double b = bench::median(bake), w = bench::median(write);
    fmt::print("{:>9} {:>10} {:>10} {:>8.3f} {:>8.3f} {:>11.2f} {:>11.1f}\n", baked.elements, triangles, vertices, b, w,
               1e6 * (b + w) / elements, bytes / elements);
    std::fflush(stdout);
  }
  std::filesystem::remove(path);
  return 0;
}
