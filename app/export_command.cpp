// radiant export SCENE -o out.glb — the radiosity solution as a mesh with
// light at its vertices, for real-time viewers (C&W §9.7; docs/export.md):
// glTF 2.0 (.glb, .gltf) or PLY. Solves first unless --solution is given.
#include <fmt/format.h>

#include <chrono>
#include <filesystem>

#include "colour_options.h"
#include "commands.h"
#include "display_options.h"
#include "export/baked_mesh.h"
#include "export/gltf_writer.h"
#include "export/lightmap_atlas.h"
#include "export/lightmap_bake.h"
#include "export/lightmap_encoding.h"
#include "export/lightmap_mesh.h"
#include "export/ply_writer.h"
#include "interrupt_handler.h"
#include "io/output_files.h"
#include "io/solution_file.h"
#include "radiosity_options.h"
#include "render/driver.h"
#include "render/emitter_coverage.h"
#include "render/film_image.h"
#include "render/registry.h"
#include "render/spectral_film.h"
#include "scene/load_scene.h"
#include "scene/spectral_scene.h"
#include "util/error.h"
#include "util/file_extension.h"
#include "util/interrupt.h"
#include "view_options.h"

namespace radiant {

namespace {

struct ExportCommandOptions {
  std::string scenePath, outputPath, solutionPath, format;
  ViewCommandOptions view;
  RadiosityCommandOptions radiosity;
  DisplayCommandOptions display;
  ColourCommandOptions colour;
  uint64_t seed = 1;
  int threads = 0;
  bool quiet = false;
  // --lightmap: the scene's own faces with the light in a texture (export/lightmap_*.h)
  bool lightmap = false;
  int lightmapSize = 1024, lightmapPadding = 4, lightmapSamples = 3;
  double texelSize = 0;
};

/// The file's format: --format, else the output's extension; the two must agree.
std::string exportFormat(const ExportCommandOptions &o) {
  const std::string extension = lowercaseExtension(o.outputPath);
  const std::string fromExtension = extension.size() > 1 ? extension.substr(1) : "";
  if (o.format.empty()) {
    if (fromExtension == "glb" || fromExtension == "gltf" || fromExtension == "ply") return fromExtension;
    throw InputError(InputLocation{"--output"},
                     "'" + o.outputPath + "': unknown extension (expected .glb, .gltf or .ply, or give --format)");
  }
  if (fromExtension != o.format)
    throw InputError(InputLocation{"--format"}, "--format " + o.format + " does not match the output '" + o.outputPath +
                                                    "' (expected ." + o.format + ")");
  return o.format;
}

/// The interpolate display of the camera's view, 4 samples per pixel: what the
/// tone operators adapt to (log-average luminance, brightest reflecting pixel),
/// exactly as they would for `radiant render --method interpolate` (one pass
/// per solution of a spectral scene, its colour formed as render forms it).
Image cameraView(Scene &scene, const RayTracer &tracer, const std::vector<Solution> &solutions, WhiteBalance balance,
                 int threads) {
  const PinholeCamera camera(scene.camera, scene.render.width, scene.render.height);
  auto renderPass = [&](int pass, Film &film) {
    RenderContext context;
    context.solution = &solutions[size_t(pass)];
    context.pixelSpreadAngle = texturePixelSpread(scene.camera, scene.render.height, 4);
    const std::unique_ptr<Renderer> renderer = createRenderer("interpolate", tracer, context);
    DriverOptions driver;
    driver.samplesPerPixel = 4;
    driver.seed = scene.render.seed;
    driver.threads = threads;
    renderImage(camera, *renderer, driver, film, {});
  };
  Image image = renderPasses(scene, scene.render.width, scene.render.height, balance, renderPass).colour;
  image.quantity = "radiance";
  image.emitterFraction = emitterCoverage(tracer, camera, image.width, image.height);
  return image;
}

/// The solutions baked, one RGB mesh (a spectral scene's passes combined); colours not set.
BakedMesh bakeSolutions(Scene &scene, const std::vector<Solution> &solutions, WhiteBalance balance) {
  if (!scene.spectral.enabled()) return bakeSolution(scene, solutions[0]);
  // Each pass refined its own mesh: the first pass's vertices, the others' light read there.
  std::vector<BakedMesh> passes;
  for (int pass = 0; pass < scene.spectral.passCount(); ++pass) {
    applySpectralPass(scene, pass);
    passes.push_back(pass == 0 ? bakeSolution(scene, solutions[0])
                               : resampleLight(passes[0], scene, solutions[size_t(pass)]));
  }
  applySpectralColour(scene, balance);
  return combineSpectralPasses(passes, scene, balance);
}

/// The operator's parameters as the file records them, named as the flags are.
std::vector<std::pair<std::string, double>> toneParameterList(const DisplaySettings &s) {
  const ToneParameters &p = s.parameters;
  std::vector<std::pair<std::string, double>> list;
  const std::string &op = s.toneOperator;
  if (op == "linear") {
    if (p.autoExposure)
      list.push_back({"key", p.key});
    else
      list.push_back({"exposure", p.exposureStops});
  }
  if (op == "max-reflected") list.push_back({"reflected-level", p.reflectedLevel});
  if (op == "reinhard" || op == "aces") list.push_back({"key", p.key});
  if (op == "reinhard" && p.whiteCdM2) list.push_back({"white", *p.whiteCdM2});
  if (op == "tumblin-rushmeier") list.push_back({"display-contrast", p.displayContrast});
  if ((op == "tumblin-rushmeier" || op == "ward") && p.displayMaxCdM2)
    list.push_back({"display-max", *p.displayMaxCdM2});
  if ((op == "tumblin-rushmeier" || op == "ward") && p.adaptationCdM2)
    list.push_back({"adaptation", *p.adaptationCdM2});
  return list;
}

/// What the glTF file records of how it was made.
ExportProvenance provenanceOf(const Solution &solution, const DisplaySettings &display, const DisplayMapping &mapping) {
  return {solution.stats.solver, display.toneOperator, toneParameterList(display), mapping.describe()};
}

/// The lightmap's irradiance beside the glTF file: out.glb → out.lightmap.exr.
std::string lightmapExrPathFor(const std::string &output) {
  std::filesystem::path path(output);
  path.replace_extension(".lightmap.exr");
  return path.string();
}

/// `radiant export --lightmap`: the scene's own faces, their light in an atlas (docs/export.md, "Lightmaps").
void writeLightmapped(const Scene &scene, const Solution &solution, const ExportCommandOptions &o,
                      const DisplaySettings &display, const DisplayMapping &mapping, const std::string &exrPath) {
  const std::vector<LightmapTriangle> triangles = lightmapTriangles(scene, solution);
  AtlasOptions atlasOptions;
  atlasOptions.size = o.lightmapSize;
  atlasOptions.texelSize = o.texelSize * scene.metresPerUnit;  // --texel-size is in the scene's units, as --mesh-size
  atlasOptions.padding = o.lightmapPadding;
  const LightmapAtlas atlas = buildLightmapAtlas(triangles, atlasOptions);
  LightmapBakeOptions bakeOptions;
  bakeOptions.samples = o.lightmapSamples;
  bakeOptions.dilation = o.lightmapPadding + 2;  // both neighbours' rings meet across the padding
  const LightmapImages images = bakeLightmap(scene, solution, triangles, atlas, bakeOptions);

  const BakedMesh baked = lightmapMesh(scene, triangles, atlas, solution.elementCount());
  GltfLightmap lightmap;
  lightmap.displayPng =
      lightmapDisplayPng(images, [&](const float radiance[3], double out[3]) { mapping.displayLinear(radiance, out); });
  lightmap.irradiancePng = lightmapIrradiancePng(images);
  lightmap.width = atlas.width;
  lightmap.height = atlas.height;
  lightmap.texelSize = atlas.texelSize;
  lightmap.charts = atlas.charts.size();
  lightmap.utilisation = double(images.coveredTexels) / (double(atlas.width) * atlas.height);
  writeGltf(scene, baked, provenanceOf(solution, display, mapping), o.outputPath, &lightmap);

  Image irradiance(atlas.width, atlas.height);
  irradiance.rgb = images.irradiance;
  irradiance.quantity = "irradiance";
  writeImage(irradiance, exrPath);
  if (!o.quiet) {
    size_t faceTriangles = 0;
    for (const BakedPrimitive &p : baked.primitives) faceTriangles += p.triangleCount();
    fmt::print(stderr,
               "radiant: lightmap {}x{} texels of {:.3g} mm, {} charts, {:.0f} % of the texels covered; {} triangles\n",
               atlas.width, atlas.height, atlas.texelSize * 1e3, atlas.charts.size(), 100 * lightmap.utilisation,
               faceTriangles);
  }
}

}  // namespace

CommandRunner addExportCommand(CLI::App &app) {
  auto o = std::make_shared<ExportCommandOptions>();
  app.add_option("scene", o->scenePath, "Scene file: JSON (docs/scene-format.md) or a bare .obj model")->required();
  app.add_option("-o,--output", o->outputPath, "The file to write: .glb, .gltf or .ply (docs/export.md)")->required();
  app.add_option("--format", o->format, "glb, gltf or ply (default: from the output's extension)")
      ->check(CLI::IsMember({"glb", "gltf", "ply"}));
  app.add_option("--solution", o->solutionPath, "Radiosity solution from `radiant solve -o` (default: solve now)");
  addViewOptions(app, o->view);
  addRadiosityOptions(app, o->radiosity);
  addDisplayOptions(app, o->display);
  addColourOptions(app, o->colour);
  app.add_option("--seed", o->seed, "Random seed of the solve and of the view the tone operator adapts to")
      ->default_val(1)
      ->check(seedRange());
  app.add_option("--threads", o->threads, "Worker threads (0: all cores); does not change the file")
      ->default_val(0)
      ->check(CLI::Range(0, 4096));
  app.add_flag("-q,--quiet", o->quiet, "No progress or summary on stderr");
  app.add_flag("--lightmap", o->lightmap,
               "Write the scene's own faces with the light in a lightmap on TEXCOORD_1 (glTF only; docs/export.md, "
               "\"Lightmaps\"), and the lightmap's irradiance as an EXR beside the file");
  app.add_option("--lightmap-size", o->lightmapSize,
                 "With --lightmap: the lightmap's side in texels; the texel size is the smallest that fits")
      ->default_val(1024)
      ->check(CLI::Range(8, kMaxLightmapSide));
  app.add_option("--texel-size", o->texelSize,
                 "With --lightmap: the texel's side in scene units (as --mesh-size) instead of --lightmap-size; the "
                 "atlas grows to fit")
      ->check(CLI::PositiveNumber);
  app.add_option("--lightmap-padding", o->lightmapPadding,
                 "With --lightmap: texels between charts, filled by dilation so that filtering does not bleed")
      ->default_val(4)
      ->check(CLI::Range(2, 64));
  app.add_option("--lightmap-samples", o->lightmapSamples,
                 "With --lightmap: samples per texel side where the texel is read from the solution")
      ->default_val(3)
      ->check(CLI::Range(1, 16));

  return [o, &app]() {
    const std::string format = exportFormat(*o);
    checkRadiosityOptions(o->radiosity, o->solutionPath.empty(), "the solution comes from --solution");
    // glTF's vertex colours are linear (the viewer applies the sRGB curve); PLY's are 8-bit display values.
    if (app.count("--bits")) throw InputError(InputLocation{"--bits"}, "exported vertex colours have no bit depth");
    if (format != "ply" && (app.count("--gamma") || app.count("--srgb")))
      throw InputError(InputLocation{app.count("--gamma") ? "--gamma" : "--srgb"},
                       "glTF vertex colours are linear: the viewer applies its display's transfer curve");
    for (const char *flag : {"--lightmap-size", "--texel-size", "--lightmap-padding", "--lightmap-samples"})
      if (app.count(flag) && !o->lightmap) throw InputError(InputLocation{flag}, "needs --lightmap");
    if (o->lightmap && format == "ply")
      throw InputError(InputLocation{"--lightmap"}, "a lightmap needs glTF (.glb or .gltf): PLY has no textures");
    if (app.count("--lightmap-size") && app.count("--texel-size"))
      throw InputError(InputLocation{"--texel-size"}, "give --lightmap-size or --texel-size, not both");
    const std::string lightmapExrPath = o->lightmap ? lightmapExrPathFor(o->outputPath) : std::string();
    std::vector<OutputFile> outputs{{o->outputPath, InputLocation{"--output"}}};
    if (o->lightmap) outputs.push_back({lightmapExrPath, InputLocation{"--lightmap"}});
    checkOutputFiles(outputs, {o->scenePath, o->solutionPath});
    InterruptHandler interrupts;
    const auto start = std::chrono::steady_clock::now();
    Scene scene = loadScene(o->scenePath);
    const WhiteBalance balance = applyColourOptions(app, o->colour, scene);
    applyViewOptions(o->view, scene);
    const DisplaySettings display = displaySettings(app, o->display, scene.render.exposure);
    if (o->lightmap && scene.spectral.enabled())
      throw InputError(InputLocation{"--lightmap"},
                       "a spectral scene's lightmap is not written yet: export it "
                       "per vertex (without --lightmap), or give the scene RGB colours");
    if (!o->quiet)
      for (const std::string &warning : scene.warnings) fmt::print(stderr, "radiant: warning: {}\n", warning);

    RayTracer tracer(scene);  // geometry only: a spectral pass changes the materials, not the rays
    // One solution for an RGB scene, one per pass of three wavelengths for a spectral one.
    std::vector<Solution> solutions;
    if (!o->solutionPath.empty()) solutions = readSolutionPasses(o->solutionPath, scene);
    const int passes = scene.spectral.enabled() ? scene.spectral.passCount() : 1;
    for (int pass = 0; solutions.empty() || int(solutions.size()) < passes; ++pass) {
      if (scene.spectral.enabled()) {
        applySpectralPass(scene, pass);
        if (!o->quiet)
          fmt::print(stderr, "radiant: solving at {} ({}/{})\n", passWavelengthLabel(scene, pass), pass + 1, passes);
      }
      solutions.push_back(solveScene(scene, tracer, o->radiosity, o->seed, o->threads, o->quiet));
    }
    if (scene.spectral.enabled()) applySpectralColour(scene, balance);
    if (interruptRequested()) throw Interrupted();

    const DisplayMapping mapping(cameraView(scene, tracer, solutions, balance, o->threads), display);
    if (!o->quiet) reportDisplayMapping(mapping, app.count("--tonemap") > 0);
    if (o->lightmap) {
      writeLightmapped(scene, solutions[0], *o, display, mapping, lightmapExrPath);
      if (!o->quiet) {
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        fmt::print(stderr, "radiant: wrote {} ({:.2f} MB) and {} in {:.2f} s\n", o->outputPath,
                   double(std::filesystem::file_size(o->outputPath)) * 1e-6, lightmapExrPath, seconds);
      }
      return 0;
    }
    BakedMesh baked = bakeSolutions(scene, solutions, balance);
    applyDisplayColours(baked, [&](const float radiance[3], double out[3]) { mapping.displayLinear(radiance, out); });
    if (format == "ply") {
      writePly(
          baked, [&](const float radiance[3], double out[3]) { mapping.encode(radiance, out); }, o->outputPath);
    } else {
      writeGltf(scene, baked, provenanceOf(solutions[0], display, mapping), o->outputPath);
    }
    if (!o->quiet) {
      size_t vertices = 0, triangles = 0;
      for (const BakedPrimitive &p : baked.primitives) vertices += p.vertexCount(), triangles += p.triangleCount();
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fmt::print(stderr, "radiant: wrote {} ({} elements, {} triangles, {} vertices, {:.2f} MB) in {:.2f} s\n",
                 o->outputPath, baked.elements, triangles, vertices,
                 double(std::filesystem::file_size(o->outputPath)) * 1e-6, seconds);
    }
    return 0;
  };
}

}  // namespace radiant
