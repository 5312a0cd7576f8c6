// Rendering helpers shared by the tests of the renderers: solve when the
// method reads a solution, render, and pick pixels by what they see.
#pragma once

#include <string>
#include <vector>

#include "radiosity/solver.h"
#include "render/driver.h"
#include "render/registry.h"
#include "render/renderer.h"

namespace radiant::test {

/// Method parameters by name, as a caller other than the command line gives them.
inline ParameterValues parameters(std::initializer_list<std::pair<std::string, std::string>> values) {
  ParameterValues given;
  for (const auto &[name, text] : values) given.set(name, text, InputLocation::ofParameter(name));
  return given;
}

/// Solves the scene (Gauss–Seidel on a uniform mesh of `meshSize` metres, to
/// `tolerance`) when `method` reads a solution, then renders `spp` samples
/// per pixel at size × size with `options` (its solution is set here).
inline Film solveAndRender(const Scene &scene, const std::string &method, RenderContext options, int spp, int size,
                           double meshSize, double tolerance = 1e-3) {
  RayTracer tracer(scene);
  Solution solution;
  if (findRenderer(method).needsSolution) {
    MeshOptions mesh;
    mesh.maxEdgeLength = meshSize;
    SolverOptions solver;
    solver.solver = "gauss-seidel";
    solver.tolerance = tolerance;
    solution = meshAndSolve(scene, tracer, mesh, solver);
    options.solution = &solution;
  }
  PinholeCamera camera(scene.camera, size, size);
  Film film(size, size);
  DriverOptions driver;
  driver.samplesPerPixel = spp;
  renderImage(camera, *createRenderer(method, tracer, options), driver, film);
  return film;
}

/// The pixels whose centre ray's first hit satisfies `select(hit)`.
template <typename Select>
std::vector<size_t> pixelsWhere(const Scene &scene, int size, Select select) {
  RayTracer tracer(scene);
  PinholeCamera camera(scene.camera, size, size);
  std::vector<size_t> pixels;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Hit hit;
      if (tracer.intersect(camera.generateRay(x + 0.5, y + 0.5), hit) && select(hit))
        pixels.push_back(size_t(y) * size + x);
    }
  return pixels;
}

}  // namespace radiant::test
