// The material of a surface exported with `radiant export --lightmap`
// (docs/export.md, "Lightmaps"): like radiance-material.js it writes the
// radiance L in W·sr⁻¹·m⁻² (or the irradiance H) into the float target, but
// reads the light from the lightmap on TEXCOORD_1 instead of the vertices:
//
//   L = L_e + ρ(x)·H(uv1)/π,  ρ(x) = baseColorFactor × baseColorTexture(uv)
//
// with H the RADIANT_lightmap extension's irradiance texture. That is
// three.js's own lightMap rule (MeshBasicMaterial: diffuse × lightMap/π,
// lightMap.channel = 1) and C&W eq. 9.11 per pixel. The irradiance is
// Radiance RGBE in an 8-bit PNG: each texel is decoded here, and the four
// around the point blended (bilinear) after decoding, never before, since
// neighbouring texels' exponents differ.
import * as THREE from 'three';
import { FRAGMENT_DECLARATIONS, OUTPUT_IRRADIANCE, radianceShaderMaterial } from './radiance-material.js';

const vertexShader = /* glsl */ `
in vec2 uv1;
out vec2 vLightmapUv;
#ifdef USE_BASE_TEXTURE
out vec2 vUv;
#endif
void main() {
  vLightmapUv = uv1;
#ifdef USE_BASE_TEXTURE
  vUv = (uBaseTextureTransform * vec3(uv, 1.0)).xy;
#endif
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`;

const fragmentShader = /* glsl */ `${FRAGMENT_DECLARATIONS}
uniform sampler2D uIrradiance;
in vec2 vLightmapUv;

// Radiance's RGBE: (c + 0.5)·2^(e − 136), e = 0 black (src/export/lightmap_encoding.h).
vec3 irradianceTexel(ivec2 p) {
  ivec2 size = textureSize(uIrradiance, 0);
  vec4 t = texelFetch(uIrradiance, clamp(p, ivec2(0), size - 1), 0);
  float e = floor(t.a * 255.0 + 0.5);
  if (e == 0.0) return vec3(0.0);
  return (floor(t.rgb * 255.0 + 0.5) + 0.5) * exp2(e - 136.0);
}

vec3 irradiance() {
  vec2 x = vLightmapUv * vec2(textureSize(uIrradiance, 0)) - 0.5;
  ivec2 i = ivec2(floor(x));
  vec2 f = x - floor(x);
  return mix(mix(irradianceTexel(i), irradianceTexel(i + ivec2(1, 0)), f.x),
             mix(irradianceTexel(i + ivec2(0, 1)), irradianceTexel(i + ivec2(1, 1)), f.x), f.y);
}

void main() {
  vec3 h = irradiance();
  if (uOutput == ${OUTPUT_IRRADIANCE}) {
    fragColor = vec4(h, uEmitter);
    return;
  }
  vec3 reflectance = uBaseColor;
#ifdef USE_BASE_TEXTURE
  reflectance *= texture(uBaseTexture, vUv).rgb;
#endif
  fragColor = vec4(uEmission + reflectance * h / 3.14159265358979, uEmitter);
}
`;

/** The material's lightmap extension, or undefined. */
export function lightmapOf(materialDef) {
  return materialDef?.extensions?.RADIANT_lightmap;
}

/**
 * A lightmap material for one glTF material.
 * @param materialDef the material's JSON, with its RADIANT_lightmap extension
 * @param irradiance the extension's irradiance texture (THREE.Texture of the RGBE PNG)
 * @param baseTexture the material's own base colour texture (sRGB), or null
 */
export function createLightmapMaterial(materialDef, irradiance, baseTexture) {
  const lightmap = lightmapOf(materialDef);
  if (lightmap.encoding !== 'rgbe' || lightmap.quantity !== 'irradiance')
    throw new Error(`material '${materialDef.name}': a RADIANT_lightmap of ${lightmap.quantity} in ${lightmap.encoding}, expected irradiance in rgbe`);
  // The bytes as they are: no colour-space conversion, no filtering across texels, no mipmaps.
  irradiance.colorSpace = THREE.NoColorSpace;
  irradiance.magFilter = irradiance.minFilter = THREE.NearestFilter;
  irradiance.generateMipmaps = false;
  irradiance.needsUpdate = true;
  if (baseTexture) {
    baseTexture.colorSpace = THREE.SRGBColorSpace;  // an albedo, decoded from sRGB before filtering
    baseTexture.needsUpdate = true;
  }
  return radianceShaderMaterial('lightmap', materialDef, lightmap.baseColorFactor ?? [1, 1, 1], baseTexture,
    { vertexShader, fragmentShader }, { uIrradiance: { value: irradiance } });
}
