// Scene loading: JSON scene files (docs/scene-format.md) and bare OBJ/MTL.
#pragma once

#include <string>

#include "scene/scene.h"

namespace radiant {

/// Loads a JSON scene or, for a path ending in .obj, a bare OBJ/MTL model with
/// a default camera framing its bounds. Throws InputError naming the file, the
/// line or JSON path, and what was expected.
Scene loadScene(const std::string &path);

/// Parses a JSON scene from text; `path` is used for messages and to resolve
/// relative mesh paths. Exposed for tests.
Scene parseSceneJson(const std::string &text, const std::string &path);

/// Appends an OBJ file's faces (with its MTL materials) to `scene`, transformed
/// by `toWorld` (which includes the unit conversion). Materials named in
/// `scene.materials` already (from the JSON) override MTL ones of the same name.
void appendObj(Scene &scene, const std::string &objPath, const Transform &toWorld, const std::string &objectName,
               int defaultMaterial);

/// Checks a loaded scene's values (finite, reflectance < 1, ...) and fills
/// warnings (no emitter, dropped faces). Throws InputError on a bad value.
void validateScene(Scene &scene);

}  // namespace radiant
