// What the adaptive operators read from the view, as radiant reads it from an
// image (display/luminance.cpp, display/emitter_mask.cpp, max_reflected.cpp).
//
// The input is the view's radiance at display resolution, one RGBA float per
// pixel read back from the GPU: RGB the pixel's mean radiance (W·sr⁻¹·m⁻²),
// A the fraction of its samples that show an emitter — what render's EXR
// "emitter" channel holds.
import { LUMINOUS_EFFICACY, relativeLuminance } from './tone-operators.js';

/**
 * @param {Float32Array} rgba width·height·4 values, rows in any order
 * @returns {{logAverage:number, maximum:number, litPixels:number, nonFinitePixels:number,
 *            brightestReflecting:number, emitterPixels:number}}
 */
export function viewStatistics(rgba, width, height) {
  // Log-average luminance over the lit pixels: black ones are left out rather
  // than offset by a δ, which would depend on the absolute level (luminance.h).
  let sumLog = 0;
  let litPixels = 0;
  let maximum = 0;
  let nonFinitePixels = 0;
  const pixels = width * height;
  for (let p = 0; p < pixels; ++p) {
    const r = rgba[4 * p];
    const g = rgba[4 * p + 1];
    const b = rgba[4 * p + 2];
    if (!Number.isFinite(r) || !Number.isFinite(g) || !Number.isFinite(b)) {
      ++nonFinitePixels;
      continue;
    }
    const luminance = LUMINOUS_EFFICACY * relativeLuminance(r, g, b);
    if (!(luminance > 0)) continue;
    sumLog += Math.log(luminance);
    if (luminance > maximum) maximum = luminance;
    ++litPixels;
  }

  // Pixels with emitter coverage and their eight neighbours do not count as
  // reflecting: a pixel at the edge of a light holds some of its radiance.
  const emitter = new Uint8Array(pixels);
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < width; ++x) {
      if (!(rgba[4 * (y * width + x) + 3] > 0)) continue;
      for (let dy = -1; dy <= 1; ++dy)
        for (let dx = -1; dx <= 1; ++dx) {
          const nx = x + dx;
          const ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < width && ny < height) emitter[ny * width + nx] = 1;
        }
    }
  // The largest channel, not luminance, so that no reflecting surface clips in any channel.
  let brightestReflecting = 0;
  let emitterPixels = 0;
  for (let p = 0; p < pixels; ++p) {
    if (emitter[p]) {
      ++emitterPixels;
      continue;
    }
    for (let c = 0; c < 3; ++c) {
      const v = rgba[4 * p + c];
      if (Number.isFinite(v) && v > brightestReflecting) brightestReflecting = v;
    }
  }
  return {
    logAverage: litPixels ? Math.exp(sumLog / litPixels) : 0,
    maximum,
    litPixels,
    nonFinitePixels,
    brightestReflecting,
    emitterPixels,
  };
}
