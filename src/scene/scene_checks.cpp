// Value checks shared by every way a scene is made (JSON, bare OBJ, code), and
// validateScene. Each check fails with what was wrong and what is allowed.

#include <algorithm>
#include <limits>
#include <sstream>

#include "scene/load_detail.h"
#include "scene/load_scene.h"
#include "scene/overlapping_faces.h"

namespace radiant {

namespace {

const char *bandName(int band) {
  static const char *names[] = {"R", "G", "B"};
  return band < 3 ? names[band] : "?";
}

std::string formatNumber(double x) {
  std::ostringstream out;
  out.precision(9);
  out << x;
  return out.str();
}

/// The location of one field: a JSON path gets the key appended; a file/line
/// location stays as it is (the message names the field).
InputLocation fieldLocation(const InputLocation &where, const char *field) {
  InputLocation at = where;
  if (!at.jsonPath.empty()) at.jsonPath += std::string("/") + field;
  return at;
}

/// fieldLocation, at the field's own MTL line when `names` knows it.
InputLocation fieldLocation(const InputLocation &where, const char *field, const detail::MaterialFieldNames &names) {
  InputLocation at = fieldLocation(where, field);
  if (auto it = names.lines.find(field); it != names.lines.end() && at.jsonPath.empty()) at.line = it->second;
  return at;
}

void checkBands(const Bands &b, const InputLocation &at, const std::string &subject, const char *field, double maximum,
                bool maximumExclusive, const char *whyMaximum) {
  for (int i = 0; i < kBandCount; ++i) {
    std::string value = std::string(field) + " " + formatNumber(b[i]) + " (band " + bandName(i) + ")";
    if (!std::isfinite(b[i])) throw InputError(at, subject + value + " is not finite");
    if (b[i] < 0) throw InputError(at, subject + value + " is negative; expected ≥ 0");
    if (maximumExclusive ? b[i] >= maximum : b[i] > maximum)
      throw InputError(
          at, subject + value + " must be " + (maximumExclusive ? "< " : "≤ ") + formatNumber(maximum) + whyMaximum);
  }
}

}  // namespace

void detail::checkMaterial(const Material &m, const InputLocation &where, const MaterialFieldNames &names) {
  const std::string subject = "material '" + m.name + "': ";
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  // ρ ≥ 1 makes B = E + ρFB a series that never converges (C&W §5.2: the
  // matrix is diagonally dominant only while every ρ < 1).
  // With a texture, ρ(x) = Kd × texel is clamped below 1 where it is used
  // (raytrace/surface_detail.h), so Kd = 1, common in MTL files with map_Kd, is fine.
  checkBands(m.diffuse, fieldLocation(where, names.diffuse, names), subject, names.diffuse, 1.0,
             m.diffuseTexture.empty(), ": a diffuse reflectance of 1 or more makes radiosity diverge");
  checkBands(m.specular, fieldLocation(where, names.specular, names), subject, names.specular, 1.0, false,
             ": a surface cannot reflect more than it receives");
  checkBands(m.emission, fieldLocation(where, names.emission, names), subject, names.emission, kInfinity, false, "");
  checkBands(m.transmittance, fieldLocation(where, names.transmittance, names), subject, names.transmittance, 1.0, true,
             ": a surface cannot pass on all the light it receives");
  if (m.isTranslucent()) {
    if (m.kind != MaterialKind::Lambertian && m.kind != MaterialKind::Glossy)
      throw InputError(where,
                       subject + names.transmittance + " applies to diffuse (lambertian, glossy) materials only");
    // ρ + τ < 1: what a translucent surface scatters, to either side, stays
    // below what it receives, or radiosity's series diverges (as for ρ alone).
    const double specular = m.kind == MaterialKind::Glossy ? 1.0 : 0.0;
    for (int i = 0; i < kBandCount; ++i) {
      const double sum = m.diffuse[i] + m.transmittance[i] + specular * m.specular[i];
      if (m.diffuse[i] + m.transmittance[i] >= 1.0 || sum > 1.0)
        throw InputError(where, subject + names.diffuse + " + " +
                                    (specular > 0 ? names.specular + std::string(" + ") : "") + names.transmittance +
                                    " = " + formatNumber(sum) + " in band " + bandName(i) +
                                    (sum > 1.0 ? " exceeds 1" : " reaches 1") +
                                    ": the surface would scatter as much light as it receives or more");
    }
  }
  if (m.kind == MaterialKind::Glossy) {
    for (int i = 0; i < kBandCount; ++i)
      if (m.diffuse[i] + m.specular[i] > 1.0)
        throw InputError(where, subject + names.diffuse + " + " + names.specular + " = " +
                                    formatNumber(m.diffuse[i] + m.specular[i]) + " in band " + bandName(i) +
                                    " exceeds 1: the surface would reflect more than it receives");
    if (!(m.roughness > 0 && m.roughness <= 1))
      throw InputError(
          fieldLocation(where, names.roughness, names),
          subject + names.roughness + " gives GGX α = " + formatNumber(m.roughness) + "; expected α in (0, 1]");
  }
  if (m.kind == MaterialKind::Dielectric && m.transmissionRoughness != 0 &&
      !(m.transmissionRoughness > 0 && m.transmissionRoughness <= 1))
    throw InputError(fieldLocation(where, names.transmissionRoughness, names),
                     subject + names.transmissionRoughness + " gives GGX α = " + formatNumber(m.transmissionRoughness) +
                         "; expected 0 (smooth glass) or α in (0, 1]");
  if (!std::isfinite(m.ior) || !(m.ior > 0))
    throw InputError(fieldLocation(where, names.ior, names), subject + names.ior + " " + formatNumber(m.ior) +
                                                                 " is not a valid index of refraction; expected > 0");
  if (!std::isfinite(m.bumpScale))
    throw InputError(fieldLocation(where, "bump_scale"), subject + "bump scale is not finite");
}

constexpr size_t kMaxReportedOverlaps = 10000;

void detail::checkCamera(const CameraSettings &c, const InputLocation &where) {
  if (!isFinite(c.eye)) throw InputError(fieldLocation(where, "eye"), "camera eye is not finite");
  if (!isFinite(c.target)) throw InputError(fieldLocation(where, "target"), "camera target is not finite");
  for (const auto &[point, name] : {std::pair{c.eye, "eye"}, std::pair{c.target, "target"}})
    if (!withinCoordinateRange(point))
      throw InputError(fieldLocation(where, name), std::string("camera ") + name + " is more than " +
                                                       formatNumber(kMaxCoordinateMetres) +
                                                       " m from the origin; the ray tracer works in single "
                                                       "precision and cannot trace rays from there");
  if (!isFinite(c.up)) throw InputError(fieldLocation(where, "up"), "camera up is not finite");
  if (!(c.verticalFovDegrees > 0 && c.verticalFovDegrees < 180))
    throw InputError(fieldLocation(where, "fov"),
                     "camera fov " + formatNumber(c.verticalFovDegrees) +
                         "° is outside (0, 180); it is the vertical field of view in degrees");
  Vec3 view = c.target - c.eye;
  if (!(length(view) > 0))
    throw InputError(fieldLocation(where, "target"), "camera target equals eye: the view direction is undefined");
  if (!(length(c.up) > 0)) throw InputError(fieldLocation(where, "up"), "camera up is the zero vector");
  if (length(cross(normalize(view), normalize(c.up))) < 1e-6)
    throw InputError(fieldLocation(where, "up"), "camera up is parallel to the view direction (target − eye)");
}

void detail::checkRenderSettings(const RenderSettings &r, const InputLocation &where) {
  constexpr int kMaxSide = 16384;
  constexpr long long kMaxPixels = 1ll << 26;
  auto imageField = [&](const char *field) {
    InputLocation at = where;
    if (!at.jsonPath.empty()) at.jsonPath = std::string("/image/") + field;
    return at;
  };
  auto renderField = [&](const char *field) {
    InputLocation at = where;
    if (!at.jsonPath.empty()) at.jsonPath = std::string("/render/") + field;
    return at;
  };
  if (r.width < 1 || r.width > kMaxSide)
    throw InputError(imageField("width"), "image width " + std::to_string(r.width) + " is outside [1, 16384]");
  if (r.height < 1 || r.height > kMaxSide)
    throw InputError(imageField("height"), "image height " + std::to_string(r.height) + " is outside [1, 16384]");
  if (static_cast<long long>(r.width) * r.height > kMaxPixels)
    throw InputError(imageField("height"), "image of " + std::to_string(r.width) + " × " + std::to_string(r.height) +
                                               " pixels exceeds the limit of 2^26 (67 108 864) pixels");
  if (r.samplesPerPixel < 1 || r.samplesPerPixel > 1048576)
    throw InputError(renderField("spp"),
                     "samples per pixel " + std::to_string(r.samplesPerPixel) + " is outside [1, 1048576]");
  if (!std::isfinite(r.timeBudgetSeconds) || r.timeBudgetSeconds < 0)
    throw InputError(renderField("time"),
                     "time budget " + formatNumber(r.timeBudgetSeconds) + " s must be finite and ≥ 0 (0: no budget)");
  if (r.maxDepth < 0)
    throw InputError(renderField("max_depth"),
                     "max depth " + std::to_string(r.maxDepth) + " must be ≥ 0 (0: unlimited)");
  if (!std::isfinite(r.exposure)) throw InputError(renderField("exposure"), "exposure is not finite");
}

void validateScene(Scene &scene) {
  const InputLocation where{scene.sourceFile, 0, 0, ""};
  for (const Material &m : scene.materials) detail::checkMaterial(m, m.definedAt.file.empty() ? where : m.definedAt);
  for (size_t i = 0; i < scene.positions.size(); ++i)
    if (!isFinite(scene.positions[i]))
      throw InputError(where, "vertex position " + std::to_string(i) + " is not finite");
    else if (!withinCoordinateRange(scene.positions[i]))
      throw InputError(where, "vertex position " + std::to_string(i) + " is more than " +
                                  formatNumber(kMaxCoordinateMetres) +
                                  " m from the origin; the ray tracer works in single precision");
  for (size_t i = 0; i < scene.normals.size(); ++i)
    if (!isFinite(scene.normals[i])) throw InputError(where, "vertex normal " + std::to_string(i) + " is not finite");
  for (size_t i = 0; i < scene.uvs.size(); ++i)
    if (!std::isfinite(scene.uvs[i]))
      throw InputError(where, "texture coordinate " + std::to_string(i / 2) + " is not finite");
  for (const Face &f : scene.faces) {
    bool valid = f.vertexCount >= 3 && f.vertexCount <= 4 && f.material < scene.materials.size() &&
                 (scene.objects.empty() || f.object < scene.objects.size());
    for (int k = 0; valid && k < f.vertexCount; ++k)
      valid = f.vertices[k] < scene.positions.size() && f.uvs[k] < static_cast<int64_t>(scene.uvs.size() / 2) &&
              f.normals[k] < static_cast<int64_t>(scene.normals.size());
    if (!valid) throw InputError(where, "a face refers to a vertex, material or object that does not exist");
  }
  scene.addBackFaces();
  // A translucent surface passes τ of what arrives on either side to the
  // other: one τ for the pair, or the light through would depend on its
  // direction (and ρ of one side + τ of the other could reach 1).
  for (const Face &f : scene.faces) {
    if (f.twin < 0 || f.back) continue;
    const Material &front = scene.materials[f.material], &back = scene.materials[scene.faces[size_t(f.twin)].material];
    const auto tau = [](const Material &m) {
      return m.kind == MaterialKind::Lambertian || m.kind == MaterialKind::Glossy ? m.transmittance : Bands(0.0);
    };
    const Bands a = tau(front), b = tau(back);
    if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2])
      throw InputError(front.definedAt.file.empty() ? where : front.definedAt,
                       "materials '" + front.name + "' and '" + back.name +
                           "' are the two sides of one surface (faces back to back), and their "
                           "diffuse_transmittance differs: the light through a surface is the same both ways; give "
                           "both sides the same diffuse_transmittance");
  }
  detail::checkCamera(scene.camera, where);
  detail::checkRenderSettings(scene.render, where);

  auto warnOnce = [&](const std::string &message) {
    if (std::find(scene.warnings.begin(), scene.warnings.end(), message) == scene.warnings.end())
      scene.warnings.push_back(message);
  };
  if (scene.droppedDegenerateFaces > 0) {
    // The first by its object and place (scene/load_changes.h), which a
    // modeller shows; `radiant info` lists more.
    std::string first;
    for (const LoadChange &c : scene.loadChanges.listed) {
      if (c.kind != LoadChangeKind::DegenerateFace) continue;
      first = "; the first in '" + (c.object < scene.objects.size() ? scene.objects[c.object].name : "?") + "'";
      if (isFinite(c.position)) {
        std::ostringstream at;
        at.precision(6);  // a place to find, not a value to compute with
        at << " at (" << c.position.x << ", " << c.position.y << ", " << c.position.z << ") m";
        first += at.str();
      }
      first += ": " + c.reason + "; radiant info lists them";
      break;
    }
    warnOnce("dropped " + std::to_string(scene.droppedDegenerateFaces) + " degenerate face" +
             (scene.droppedDegenerateFaces == 1 ? "" : "s") + " (zero area or not finite" + first + ")");
  }
  if (scene.faces.empty()) warnOnce("the scene has no faces");
  if (const std::vector<FaceOverlap> overlaps = findOverlappingFaces(scene, kMaxReportedOverlaps); !overlaps.empty())
    warnOnce(describeOverlappingFaces(scene, overlaps) + (overlaps.size() >= kMaxReportedOverlaps ? " or more" : "") +
             ": each receives all the light that reaches the plane, so radiosity counts it twice; keep one copy");
  bool anyEmitter = !scene.lights.empty();
  for (const Face &f : scene.faces) anyEmitter = anyEmitter || scene.materials[f.material].isEmitter();
  if (!anyEmitter) warnOnce("no emitter and no light: the image will be black");
}

}  // namespace radiant
