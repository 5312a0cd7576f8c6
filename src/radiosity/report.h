// Per-surface report of a solution, in the units lighting designers read.
#pragma once

#include <span>
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
/// The same for a spectral scene's passes (one solution per pass): the R, G, B
/// columns hold linear sRGB formed from the spectrum (CIE 1931, then
/// `balance`), luminance and illuminance its Y; one more column per
/// wavelength holds the spectral radiosity in W·m⁻²·nm⁻¹.
void writeSurfaceReport(std::span<const Solution> passes, const Scene &scene, const std::string &path,
                        WhiteBalance balance);

}  // namespace radiant
