#include "view_options.h"

#include <fmt/format.h>

#include <sstream>

#include "util/error.h"

namespace radiant {

namespace {

Vec3 parseVector(const std::string &text, const std::string &flagName) {
  Vec3 v;
  char c1 = 0, c2 = 0;
  std::istringstream in(text);
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !isFinite(v) || !(in >> std::ws).eof())
    throw InputError(InputLocation{flagName},
                     "expected three comma-separated numbers like 1,2.5,-3, got '" + text + "'");
  return v;
}

}  // namespace

void addViewOptions(CLI::App &app, ViewCommandOptions &o) {
  app.add_option("--eye", o.eye, "Camera position x,y,z in scene units (overrides the scene)");
  app.add_option("--target", o.target, "Camera target x,y,z in scene units");
  app.add_option("--up", o.up, "Camera up vector x,y,z");
  app.add_option("--fov", o.fov, "Vertical field of view, degrees");
  app.add_option("--width", o.width, "Image width, pixels");
  app.add_option("--height", o.height, "Image height, pixels");
}

void applyViewOptions(const ViewCommandOptions &o, Scene &scene) {
  const double unit = scene.metresPerUnit;
  if (!o.eye.empty()) scene.camera.eye = parseVector(o.eye, "--eye") * unit;
  if (!o.target.empty()) scene.camera.target = parseVector(o.target, "--target") * unit;
  if (!o.up.empty()) scene.camera.up = parseVector(o.up, "--up");
  if (o.fov) scene.camera.verticalFovDegrees = *o.fov;
  if (o.width) scene.render.width = *o.width;
  if (o.height) scene.render.height = *o.height;

  const RenderSettings &r = scene.render;
  if (r.width < 1 || r.height < 1 || r.width > kMaxImageDimension || r.height > kMaxImageDimension ||
      static_cast<long long>(r.width) * r.height > kMaxImagePixels)
    throw InputError(InputLocation{"--width/--height"},
                     fmt::format("image size {}x{} is out of range (each side 1..{}, at most {} pixels)", r.width,
                                 r.height, kMaxImageDimension, kMaxImagePixels));
  if (!(scene.camera.verticalFovDegrees > 0 && scene.camera.verticalFovDegrees < 180))
    throw InputError(InputLocation{"--fov"}, "the field of view must be strictly between 0 and 180 degrees");
  for (const Vec3 &point : {scene.camera.eye, scene.camera.target})
    if (!withinCoordinateRange(point))
      throw InputError(InputLocation{"--eye/--target"},
                       fmt::format("the camera is more than {:g} m from the origin; the ray tracer works in single "
                                   "precision and cannot trace rays from there",
                                   kMaxCoordinateMetres));
  const Vec3 view = scene.camera.target - scene.camera.eye;
  if (!(length(view) > 0) || !(length(cross(normalize(view), normalize(scene.camera.up))) > 1e-6))
    throw InputError(InputLocation{"--eye/--target/--up"},
                     "the camera needs eye ≠ target and an up vector not parallel to the view direction");
}

}  // namespace radiant
