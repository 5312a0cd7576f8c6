// Illuminance on calculation grids (the scene's "grids"), measured from a
// radiosity solution the way Radiance's `rtrace -I` measures it: per point,
// a gather over the hemisphere of the measuring plane's normal.
//
// At a point x with normal n the illuminance is
//   E(x) = E_direct(x) + ∫ L_r(y(ω)) cos θ dω,
// E_direct: the emitters' light straight to x, exact (backprojection,
// radiosity/backprojection.h's DirectIrradiance: Σ π L_e F(x → visible part),
// visibility sampled on a fixed lattice past many occluders, so no noise);
// the integral: N cosine-distributed gather rays, each reading the
// *reflected* radiance (B − E)/π of the surface it hits from the solution
// (radiosity/solution_query.h), so E_indirect ≈ π/N Σ L_r. Emission is never
// read by a gather ray: it is all in E_direct, counted once (the split of
// shirley, C&W §9.3.1). Photometric: lux = 683 lm/W × Y, Y the Rec.709
// luminance row of the RGB bands, or the CIE ȳ integral of a spectral
// scene's passes (as radiosity/report.h).
//
// The standard error of each point is the gather's sample standard deviation
// over √N (pass variances added; the direct part has none). Gather rays are
// drawn in batches of 256 until the standard error is below
// GridOptions::targetRelativeError of the point's E, or maxSamples.
// Deterministic for a seed: every point draws from its own generator
// (seed, grid, point, pass), whatever the threads.
//
// Not measured: light through glass or off mirrors (the solution holds
// diffuse transport only; a gather ray that hits a face with no patch reads
// 0), and diffuse textures (the solution's mean reflectance is read).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "radiosity/solution.h"
#include "raytrace/ray_tracer.h"
#include "scene/scene.h"

namespace radiant {

struct GridOptions {
  int maxSamples = 16384;              ///< gather rays per point and pass, at most
  int minSamples = 256;                ///< gather rays per point and pass, at least
  double targetRelativeError = 0.005;  ///< stop when standard error ≤ this × E
  uint64_t seed = 1;
  int threads = 0;  ///< 0: all cores; does not change the result
};

struct GridPointIlluminance {
  Vec3 position;                ///< metres
  double illuminanceLux = 0;    ///< direct + indirect
  double directLux = 0;         ///< from the emitters, exact
  double indirectLux = 0;       ///< gathered from the solution's reflected light
  double standardErrorLux = 0;  ///< of illuminanceLux
  int samples = 0;              ///< gather rays (summed over passes)
};

struct GridIlluminance {
  CalculationGrid grid;
  std::vector<GridPointIlluminance> points;  ///< point (i, j) at index j·nu + i
  double minimumLux = 0, averageLux = 0, maximumLux = 0;
  /// U₀ = E_min/E_avg and U_d = E_min/E_max (EN 12464-1); 0 where E_avg or E_max is 0.
  double uniformity() const { return averageLux > 0 ? minimumLux / averageLux : 0; }
  double diversity() const { return maximumLux > 0 ? minimumLux / maximumLux : 0; }
  const GridPointIlluminance &at(int i, int j) const { return points[size_t(j) * size_t(grid.nu) + size_t(i)]; }
};

/// The illuminance on every grid of the scene, from its solution (one per
/// spectral pass). A spectral scene is left in its last pass
/// (applySpectralPass): the caller forms its colours after.
std::vector<GridIlluminance> computeGridIlluminance(Scene &scene, const RayTracer &tracer,
                                                    std::span<const Solution> passes, const GridOptions &options);

/// The CSV of docs/scene-format.md ("grids"): one row per point, columns
/// grid,i,j,x,y,z,illuminance_lux,standard_error_lux,direct_lux,indirect_lux,samples
/// (positions in the scene's units, `metresPerUnit` metres each), then one
/// summary per grid as comment lines starting with '#'. Written atomically.
/// `lights`, when given, are listed in comment lines after the summaries,
/// with their flux (lm) and peak intensity (cd).
void writeGridReport(const std::vector<GridIlluminance> &grids, double metresPerUnit, const std::string &path,
                     std::span<const PointLight> lights = {});

}  // namespace radiant
