// Per-surface report of a solution, in the units lighting designers read.
#pragma once

#include <string>

#include "radiosity/solution.h"
#include "scene/scene.h"

namespace radiant {

/// One CSV row per input object (JSON object or OBJ object/group): area (m²),
/// mean radiosity and irradiance per band (W·m⁻²), and their photometric
/// equivalents: luminance (cd/m², 683 lm/W × the Rec.709 luminance row of
/// B/π) and illuminance (lux, the same weighting of H). Area-weighted means
/// over the object's elements. Written atomically.
void writeSurfaceReport(const Solution &solution, const Scene &scene, const std::string &path);

}  // namespace radiant
