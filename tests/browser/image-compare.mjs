// Comparing two display images the way the viewer's test needs: the ratio of
// their mean luminance (linear, so a ratio of light) and the structural
// similarity of their luminance.
//
// SSIM is Wang, Bovik, Sheikh & Simoncelli, "Image quality assessment: from
// error visibility to structural similarity", IEEE TIP 13(4), 2004: eq. 13
// with an 11 × 11 circular-symmetric Gaussian window, σ = 1.5 samples,
// normalised to unit sum; K1 = 0.01, K2 = 0.03, L = 255; the mean SSIM over
// the windows that lie wholly inside the image (eq. 17). It is computed on the
// luminance re-encoded with the sRGB curve, 0…255: a perceptual scale, as the
// paper's 8-bit grey images are.
import { linearLuminance } from './harness.mjs';

const srgbEncode = (v) => (v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055);

/** Mean relative luminance (linear) of an 8-bit sRGB image {width, height, rgb}. */
export function meanLuminance(image) {
  const y = linearLuminance(image);
  let sum = 0;
  for (const v of y) sum += v;
  return sum / y.length;
}

function gaussianWindow(radius, sigma) {
  const w = [];
  let sum = 0;
  for (let i = -radius; i <= radius; ++i) {
    const v = Math.exp(-(i * i) / (2 * sigma * sigma));
    w.push(v);
    sum += v;
  }
  return w.map((v) => v / sum);
}

/** The Gaussian-weighted mean of `values` around every pixel whose window lies inside: (w−2r)·(h−2r) values. */
function filterValid(values, width, height, window) {
  const r = (window.length - 1) / 2;
  const outW = width - 2 * r;
  const outH = height - 2 * r;
  const rows = new Float64Array(outW * height);
  for (let y = 0; y < height; ++y)
    for (let x = 0; x < outW; ++x) {
      let s = 0;
      for (let k = 0; k < window.length; ++k) s += window[k] * values[y * width + x + k];
      rows[y * outW + x] = s;
    }
  const out = new Float64Array(outW * outH);
  for (let y = 0; y < outH; ++y)
    for (let x = 0; x < outW; ++x) {
      let s = 0;
      for (let k = 0; k < window.length; ++k) s += window[k] * rows[(y + k) * outW + x];
      out[y * outW + x] = s;
    }
  return out;
}

/** Mean SSIM of the luminance of two images of the same size. */
export function ssimLuminance(a, b) {
  if (a.width !== b.width || a.height !== b.height)
    throw new Error(`SSIM: sizes differ (${a.width}×${a.height} and ${b.width}×${b.height})`);
  const { width, height } = a;
  const encode = (image) => linearLuminance(image).map((v) => 255 * srgbEncode(v));
  const x = encode(a);
  const y = encode(b);
  const xx = x.map((v) => v * v);
  const yy = y.map((v) => v * v);
  const xy = x.map((v, i) => v * y[i]);
  const window = gaussianWindow(5, 1.5);
  const [mx, my, sxx, syy, sxy] = [x, y, xx, yy, xy].map((v) => filterValid(v, width, height, window));
  const c1 = (0.01 * 255) ** 2;
  const c2 = (0.03 * 255) ** 2;
  let sum = 0;
  for (let i = 0; i < mx.length; ++i) {
    const varX = sxx[i] - mx[i] * mx[i];
    const varY = syy[i] - my[i] * my[i];
    const cov = sxy[i] - mx[i] * my[i];
    sum += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (varX + varY + c2));
  }
  return sum / mx.length;
}

/** What the test reports and checks: {meanRatio: viewer / radiant, ssim}. */
export function compareImages(viewer, reference) {
  return { meanRatio: meanLuminance(viewer) / meanLuminance(reference), ssim: ssimLuminance(viewer, reference) };
}
