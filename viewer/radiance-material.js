// The material every exported surface is drawn with: it writes the surface's
// radiance L (or irradiance H) in W·sr⁻¹·m⁻², linear Rec.709, into a float
// target, never a display value. Display mapping happens afterwards on the
// whole view (display-pass.js), as radiant maps a rendered image.
//
// L follows docs/export.md "Reading the light in a viewer":
//   untextured:  L = _RADIANCE, interpolated linearly over the triangle;
//   textured:    L = L_e + ρ(x)·_IRRADIANCE/π, ρ(x) = baseColorFactor × texture
//                (the texture sRGB-decoded by the GPU before filtering),
//                i.e. C&W eq. 9.11 per pixel.
// Alpha carries 1 on emitters: the view's emitter coverage, which
// max-reflected leaves out (statistics.js).
import * as THREE from 'three';

export const OUTPUT_RADIANCE = 0;
export const OUTPUT_IRRADIANCE = 1;

const vertexShader = /* glsl */ `
in vec3 _radiance;
in vec3 _irradiance;
out vec3 vRadiance;
out vec3 vIrradiance;
#ifdef USE_BASE_TEXTURE
out vec2 vUv;
#endif
void main() {
  vRadiance = _radiance;
  vIrradiance = _irradiance;
#ifdef USE_BASE_TEXTURE
  vUv = (uBaseTextureTransform * vec3(uv, 1.0)).xy;
#endif
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}
`;

/** What every radiance fragment shader declares: the output switch, ρ, L_e, the emitter flag, the texture, the target. */
export const FRAGMENT_DECLARATIONS = /* glsl */ `
precision highp float;
uniform int uOutput;
uniform vec3 uBaseColor;
uniform vec3 uEmission;
uniform float uEmitter;
#ifdef USE_BASE_TEXTURE
uniform sampler2D uBaseTexture;
in vec2 vUv;
#endif
layout(location = 0) out vec4 fragColor;
`;

const fragmentShader = /* glsl */ `${FRAGMENT_DECLARATIONS}
in vec3 vRadiance;
in vec3 vIrradiance;
void main() {
  if (uOutput == ${OUTPUT_IRRADIANCE}) {
    fragColor = vec4(vIrradiance, uEmitter);
    return;
  }
#ifdef USE_BASE_TEXTURE
  vec3 reflectance = uBaseColor * texture(uBaseTexture, vUv).rgb;
  fragColor = vec4(uEmission + reflectance * vIrradiance / 3.14159265358979, uEmitter);
#else
  fragColor = vec4(vRadiance, uEmitter);
#endif
}
`;

/** Emitted radiance L_e of a glTF material: emissiveFactor × KHR_materials_emissive_strength (docs/export.md). */
export function emissionOf(materialDef) {
  const radiant = materialDef?.extras?.radiant;
  if (radiant && Array.isArray(radiant.emission) && radiant.emission.length === 3) return radiant.emission.map(Number);
  const factor = materialDef?.emissiveFactor ?? [0, 0, 0];
  const strength = materialDef?.extensions?.KHR_materials_emissive_strength?.emissiveStrength ?? 1;
  return factor.map((f) => f * strength);
}

/**
 * A radiance material for one glTF material.
 * @param materialDef the material's JSON (gltf.parser.json.materials[i]), or undefined
 * @param loaded the material three's GLTFLoader made of it (for its texture and side)
 */
export function createRadianceMaterial(materialDef, loaded) {
  const baseColor = materialDef?.pbrMetallicRoughness?.baseColorFactor ?? [1, 1, 1, 1];
  const texture = loaded?.map && materialDef?.pbrMetallicRoughness?.baseColorTexture ? loaded.map : null;
  return radianceShaderMaterial('radiance', materialDef, baseColor, texture, { vertexShader, fragmentShader });
}

/**
 * A shader material that writes radiance for one glTF material: the uniforms FRAGMENT_DECLARATIONS
 * declares (ρ = baseColor, L_e from the material), the base texture and its transform when there is one
 * (USE_BASE_TEXTURE; `uBaseTextureTransform` is declared here for the vertex shader), and `uniforms` more.
 */
export function radianceShaderMaterial(kind, materialDef, baseColor, texture, shaders, uniforms = {}) {
  const emission = emissionOf(materialDef);
  const defines = {};
  const all = {
    uOutput: { value: OUTPUT_RADIANCE },
    uBaseColor: { value: new THREE.Vector3(baseColor[0], baseColor[1], baseColor[2]) },
    uEmission: { value: new THREE.Vector3(...emission) },
    uEmitter: { value: emission.some((e) => e > 0) ? 1 : 0 },
    ...uniforms,
  };
  if (texture) {
    defines.USE_BASE_TEXTURE = '';
    texture.updateMatrix();
    all.uBaseTexture = { value: texture };
    all.uBaseTextureTransform = { value: texture.matrix };
  }
  return new THREE.ShaderMaterial({
    name: `${kind}:${materialDef?.name ?? ''}`,
    glslVersion: THREE.GLSL3,
    vertexShader: texture ? `uniform mat3 uBaseTextureTransform;\n${shaders.vertexShader}` : shaders.vertexShader,
    fragmentShader: shaders.fragmentShader,
    uniforms: all,
    defines,
    side: materialDef?.doubleSided ? THREE.DoubleSide : THREE.FrontSide,
  });
}
