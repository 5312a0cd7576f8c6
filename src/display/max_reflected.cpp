// `max-reflected` — the ad-hoc normalisation of radiosity practice that
// Tumblin & Rushmeier 1993 describe (sidebar "Why tone reproduction matters"):
// divide every radiance by that of the brightest non-emitting surface in view,
// so it shows just below full scale, and let the light sources saturate.
//
//   I/k = level · L / L_refl,  L_refl = the largest channel value of any pixel that shows no emitter
//
// The largest *channel* rather than the largest luminance, so that no
// reflecting surface clips in any channel (a saturated red wall has R above its
// luminance). level = --reflected-level, default 0.95: 5 % headroom keeps the
// brightest wall distinguishable from the clamped lights.
//
// Which pixels show an emitter comes from the image's emitter coverage (the
// "emitter" channel render writes in its EXR); pixels with coverage and their
// neighbours are left out (display/emitter_mask.h). An image without it —
// a PFM, an EXR from elsewhere — is treated as showing no emitter: the lights
// then set the scale and the room comes out dark, and a warning says so.
//
// The result does not depend on the absolute level: a scene lit by fireflies and
// the same scene lit by a searchlight display identically, which is exactly the
// flaw tone reproduction addresses.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "display/emitter_mask.h"
#include "display/tone_operator.h"

namespace radiant {

std::unique_ptr<ToneOperator> createMaxReflectedOperator(const Image &radiance, const ToneParameters &p,
                                                         ToneWarnings &warnings) {
  const bool known = !radiance.emitterFraction.empty();
  if (!known)
    warnings.push_back(
        "max-reflected: the image does not say which pixels show light sources (no \"emitter\" channel; render's EXR "
        "has one), so every pixel counts as reflecting and the brightest, perhaps a light, sets the scale");
  const std::vector<uint8_t> emitter = emitterPixelMask(radiance);
  double brightest = 0;
  size_t excluded = 0;
  for (size_t i = 0; i < emitter.size(); ++i) {
    if (emitter[i]) {
      ++excluded;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      float v = radiance.rgb[3 * i + c];
      if (std::isfinite(v)) brightest = std::max(brightest, double(v));
    }
  }
  if (!(brightest > 0)) {
    warnings.push_back("max-reflected: no lit reflecting pixel; scale 1");
    return createScaleOperator(1.0, "max-reflected: no lit reflecting pixel, scale 1");
  }
  return createScaleOperator(
      p.reflectedLevel / brightest,
      fmt::format("max-reflected: brightest reflecting pixel {:.4g} W/(sr·m²) shown at {:.3g}; {} pixels near "
                  "emitters left out",
                  brightest, p.reflectedLevel, excluded));
}

}  // namespace radiant
