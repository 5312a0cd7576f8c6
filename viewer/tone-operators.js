// The tone operators of `radiant tonemap` (src/display/*.cpp,
// docs/tone-mapping.md), for the viewer: the same parameters with the same
// defaults, the same constants taken from the image, and a GLSL `toneMap`
// with the same per-pixel formulas, so that the same settings give the same
// pixels as radiant's PNG.
//
// An operator is built like radiant's: `create(statistics, parameters)` reads
// what it adapts to (statistics.js, from the current view) and returns the
// uniforms of the shader and a line for the overlay. The GLSL has four kinds:
//   scale     I/k = scale · L per channel (linear, max-reflected, ward)
//   reinhard  Reinhard et al. 2002 eq. 2–4 on luminance, colour scaled by L_d/L_w
//   aces      Hill's fit of the ACES RRT+ODT after an exposure
//   tumblin   Tumblin & Rushmeier 1993 eq. 13 in lamberts, I/k = L_d/L_dmax − 1/C_max
// What follows — the gamut rule (clip) and the sRGB curve — is DISPLAY_GLSL.

export const LUMINOUS_EFFICACY = 683; // lm/W, K_m (display/luminance.h)
export const LUMINANCE_WEIGHTS = [0.212639, 0.7151687, 0.0721923]; // Y row of linear sRGB → XYZ
const LAMBERTS_PER_CD_M2 = 3.14159265358979323846e-4;

export function relativeLuminance(r, g, b) {
  return LUMINANCE_WEIGHTS[0] * r + LUMINANCE_WEIGHTS[1] * g + LUMINANCE_WEIGHTS[2] * b;
}

const KIND = { scale: 0, reinhard: 1, aces: 2, tumblin: 3 };

function scaleOperator(scale, describe) {
  return { kind: KIND.scale, scale, describe };
}

function keyExposureScale(stats, key) {
  return (key * LUMINOUS_EFFICACY) / stats.logAverage;
}

// Tumblin & Rushmeier 1993 eq. 9, 10 (lamberts).
const trAlpha = (la) => 0.4 * Math.log10(la) + 2.92;
function trBeta(la) {
  const x = Math.log10(la);
  return -0.4 * x * x - 2.584 * x + 2.0208;
}

const fmt = (x, digits = 4) => (Number.isFinite(x) ? Number(x.toPrecision(digits)).toString() : String(x));

/**
 * The operators, in radiant's registry order (display/tone_registry.cpp).
 * `parameters`: name as on radiant's command line, default (null: none), the range radiant accepts,
 * step (and the exposure's slider range) for the UI.
 * `adaptive`: whether the result depends on the view (then statistics are recomputed as it changes).
 */
export const TONE_OPERATORS = [
  {
    name: 'linear',
    summary: 'radiance × 2^exposure',
    parameters: [
      { name: 'exposure', label: 'Exposure (stops)', default: 0, min: -Infinity, max: Infinity, slider: [-10, 10], step: 0.1, auto: true },
      { name: 'key', label: 'Key (with auto)', default: 0.18, min: 1e-9, max: Infinity, step: 0.01 },
    ],
    adaptive: (p) => p.exposure === 'auto',
    create(stats, p) {
      if (p.exposure !== 'auto') return scaleOperator(2 ** p.exposure, `linear: exposure ${fmt(p.exposure, 3)} stops`);
      if (stats.litPixels === 0) return scaleOperator(1, 'linear: exposure auto (black image), 0 stops');
      const scale = keyExposureScale(stats, p.key);
      return scaleOperator(
        scale,
        `linear: exposure auto ${fmt(Math.log2(scale), 3)} stops (log-average ${fmt(stats.logAverage)} cd/m² shown at ${fmt(p.key, 3)})`,
      );
    },
  },
  {
    name: 'max-reflected',
    summary: 'brightest non-emitting pixel at reflected-level, lights clamp',
    parameters: [{ name: 'reflected-level', label: 'Reflected level', default: 0.95, min: 1e-6, max: 1, step: 0.01 }],
    adaptive: () => true,
    create(stats, p) {
      const brightest = stats.brightestReflecting;
      if (!(brightest > 0)) return scaleOperator(1, 'max-reflected: no lit reflecting pixel, scale 1');
      return scaleOperator(
        p['reflected-level'] / brightest,
        `max-reflected: brightest reflecting pixel ${fmt(brightest)} W/(sr·m²) shown at ${fmt(p['reflected-level'], 3)}; ` +
          `${stats.emitterPixels} pixels near emitters left out`,
      );
    },
  },
  {
    name: 'tumblin-rushmeier',
    summary: 'Tumblin & Rushmeier 1993 brightness matching (absolute)',
    parameters: [
      { name: 'display-max', label: 'Display max (cd/m²)', default: 86, min: 1e-9, max: Infinity, step: 1 },
      { name: 'display-contrast', label: 'Display contrast', default: 35, min: 1.000001, max: 1e9, step: 1 },
      { name: 'adaptation', label: 'Adaptation (cd/m²)', default: null, min: 1e-9, max: Infinity, step: 'any' },
    ],
    adaptive: (p) => p.adaptation === null,
    create(stats, p) {
      const displayMax = p['display-max'];
      const contrast = p['display-contrast'];
      let adaptation;
      let origin;
      if (p.adaptation !== null) {
        adaptation = p.adaptation;
        origin = 'given';
      } else if (stats.litPixels === 0) {
        adaptation = displayMax / Math.sqrt(contrast);
        origin = 'black image';
      } else {
        adaptation = stats.logAverage * 10 ** 0.84; // eq. 11
        origin = `log-average ${fmt(stats.logAverage)} cd/m² × 10^0.84, eq. 11`;
      }
      const displayAdaptation = displayMax / Math.sqrt(contrast); // eq. 14
      const wa = adaptation * LAMBERTS_PER_CD_M2;
      const da = displayAdaptation * LAMBERTS_PER_CD_M2;
      return {
        kind: KIND.tumblin,
        exponent: trAlpha(wa) / trAlpha(da),
        factor: 10 ** ((trBeta(wa) - trBeta(da)) / trAlpha(da)),
        displayMax,
        contrast,
        describe: `tumblin-rushmeier: world adaptation ${fmt(adaptation)} cd/m² (${origin}), display ${fmt(displayMax)} cd/m² maximum, contrast ${fmt(contrast, 3)}`,
      };
    },
  },
  {
    name: 'ward',
    summary: 'Ward 1994 contrast-based scale factor (absolute)',
    parameters: [
      { name: 'display-max', label: 'Display max (cd/m²)', default: 100, min: 1e-9, max: Infinity, step: 1 },
      { name: 'adaptation', label: 'Adaptation (cd/m²)', default: null, min: 1e-9, max: Infinity, step: 'any' },
    ],
    adaptive: (p) => p.adaptation === null,
    create(stats, p) {
      const displayMax = p['display-max'];
      const adaptation = p.adaptation !== null ? p.adaptation : stats.logAverage;
      const m = ((1.219 + (displayMax / 2) ** 0.4) / (1.219 + adaptation ** 0.4)) ** 2.5;
      return scaleOperator(
        (LUMINOUS_EFFICACY * m) / displayMax,
        `ward: world adaptation ${fmt(adaptation)} cd/m² (${p.adaptation !== null ? 'given' : 'log-average'}), display ${fmt(displayMax)} cd/m² maximum, m = ${fmt(m)}`,
      );
    },
  },
  {
    name: 'reinhard',
    summary: 'Reinhard et al. 2002 global operator',
    parameters: [
      { name: 'key', label: 'Key', default: 0.18, min: 1e-9, max: Infinity, step: 0.01 },
      { name: 'white', label: 'White (cd/m²)', default: null, unset: 'none', min: 1e-9, max: Infinity, step: 'any' },
    ],
    adaptive: () => true,
    create(stats, p) {
      if (stats.litPixels === 0) return { kind: KIND.reinhard, scale: 0, white: -1, describe: 'reinhard: black image' };
      const scale = p.key / stats.logAverage; // per cd/m²
      return {
        kind: KIND.reinhard,
        scale,
        white: p.white !== null ? p.white * scale : -1,
        describe: `reinhard: key ${fmt(p.key, 3)}, log-average ${fmt(stats.logAverage)} cd/m², ${p.white !== null ? `white ${fmt(p.white)} cd/m²` : 'no white point'}`,
      };
    },
  },
  {
    name: 'aces',
    summary: "Hill's fit of the ACES RRT+ODT, exposed by key",
    parameters: [{ name: 'key', label: 'Key', default: 0.18, min: 1e-9, max: Infinity, step: 0.01 }],
    adaptive: () => true,
    create(stats, p) {
      if (stats.litPixels === 0) return { kind: KIND.aces, scale: 1, describe: 'aces: black image' };
      return {
        kind: KIND.aces,
        scale: keyExposureScale(stats, p.key),
        describe: `aces (Hill's RRT+ODT fit): log-average ${fmt(stats.logAverage)} cd/m² exposed to ${fmt(p.key, 3)}`,
      };
    },
  },
];

export function findToneOperator(name) {
  const op = TONE_OPERATORS.find((o) => o.name === name);
  if (!op) throw new Error(`unknown tone operator '${name}'; known: ${TONE_OPERATORS.map((o) => o.name).join(', ')}`);
  return op;
}

/** The operator's parameters with defaults filled in; `given` maps names to strings (URL) or numbers. */
export function toneParameters(op, given = {}) {
  const p = {};
  for (const spec of op.parameters) {
    const value = given[spec.name];
    if (value === undefined || value === null || value === '') {
      p[spec.name] = spec.default;
    } else if (spec.auto && String(value) === 'auto') {
      p[spec.name] = 'auto';
    } else {
      const x = Number(value);
      if (!Number.isFinite(x)) throw new Error(`${spec.name}: expected a number${spec.auto ? ' or auto' : ''}, got '${value}'`);
      if (x < spec.min || x > spec.max) throw new Error(`${spec.name}: ${x} is outside [${spec.min}, ${spec.max}]`);
      p[spec.name] = x;
    }
  }
  return p;
}

/** Sets the uniforms of TONE_MAP_GLSL from what `create` returned. */
export function setToneUniforms(uniforms, mapped) {
  uniforms.uToneKind.value = mapped.kind;
  uniforms.uToneScale.value = mapped.scale ?? 1;
  uniforms.uToneWhite.value = mapped.white ?? -1;
  uniforms.uTrExponent.value = mapped.exponent ?? 1;
  uniforms.uTrFactor.value = mapped.factor ?? 1;
  uniforms.uTrDisplayMax.value = mapped.displayMax ?? 1;
  uniforms.uTrContrast.value = mapped.contrast ?? 1;
}

export function toneUniforms() {
  return {
    uToneKind: { value: 0 },
    uToneScale: { value: 1 },
    uToneWhite: { value: -1 },
    uTrExponent: { value: 1 },
    uTrFactor: { value: 1 },
    uTrDisplayMax: { value: 1 },
    uTrContrast: { value: 1 },
  };
}

// Steps 1–3 of display/display_mapping.h: operator, gamut rule `clip`, sRGB
// curve (quantisation is the frame buffer's). Comparisons are written as
// radiant's `!(x > 0)` so that NaN goes to 0 as it does there.
export const TONE_MAP_GLSL = /* glsl */ `
uniform int uToneKind;
uniform float uToneScale;
uniform float uToneWhite;
uniform float uTrExponent;
uniform float uTrFactor;
uniform float uTrDisplayMax;
uniform float uTrContrast;

const vec3 kLuminanceWeights = vec3(0.2126390, 0.7151687, 0.0721923);
const float kLuminousEfficacy = 683.0;
const float kLambertsPerCdM2 = 3.14159265358979323846e-4;

vec3 scaleToLuminance(vec3 radiance, float displayLuminance) {
  float luminance = dot(kLuminanceWeights, radiance);
  float ratio = (luminance > 0.0 && displayLuminance > 0.0) ? displayLuminance / luminance : 0.0;
  return radiance * ratio;
}

vec3 acesFitted(vec3 c) {
  // Rows of radiant's kAcesInput / kAcesOutput (display/aces.cpp); GLSL matrices are column-major.
  const mat3 acesInput = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
  const mat3 acesOutput = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
  vec3 v = acesInput * c;
  vec3 fitted = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081);
  return clamp(acesOutput * fitted, 0.0, 1.0);
}

vec3 toneMap(vec3 radiance) {
  if (uToneKind == 0) return radiance * uToneScale;
  if (uToneKind == 1) {
    float l = uToneScale * kLuminousEfficacy * dot(kLuminanceWeights, radiance);
    float ld = 0.0;
    if (l > 0.0) ld = uToneWhite > 0.0 ? l * (1.0 + l / (uToneWhite * uToneWhite)) / (1.0 + l) : l / (1.0 + l);
    return scaleToLuminance(radiance, ld);
  }
  if (uToneKind == 2) return acesFitted(radiance * uToneScale);
  float world = kLuminousEfficacy * dot(kLuminanceWeights, radiance);
  float display = world > 0.0 ? pow(world * kLambertsPerCdM2, uTrExponent) * uTrFactor / kLambertsPerCdM2 : 0.0;
  return scaleToLuminance(radiance, max(0.0, display / uTrDisplayMax - 1.0 / uTrContrast));
}

float srgbEncode(float linear) {
  if (!(linear > 0.0)) return 0.0;
  if (linear >= 1.0) return 1.0;
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

// Radiance (W·sr⁻¹·m⁻², linear Rec.709) → the encoded value radiant's PNG holds.
vec3 displayMapping(vec3 radiance) {
  vec3 display = toneMap(radiance);
  for (int c = 0; c < 3; ++c) display[c] = display[c] > 0.0 ? min(display[c], 1.0) : 0.0;  // gamut rule: clip
  return vec3(srgbEncode(display.r), srgbEncode(display.g), srgbEncode(display.b));
}
`;
