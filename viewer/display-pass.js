// From the view's radiance (a float target, `supersample`² samples per pixel)
// to pixels, as radiant goes from a rendered image to its PNG: first each
// pixel's mean radiance (a box filter over its samples, as the film averages
// its samples), then the display mapping of that mean (tone-operators.js).
// The same pass, with the mapping off, writes the per-pixel means into a
// float target that is read back for the statistics the operators adapt to.
import * as THREE from 'three';
import { TONE_MAP_GLSL, toneUniforms } from './tone-operators.js';

const vertexShader = /* glsl */ `
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }
`;

const fragmentShader = /* glsl */ `
precision highp float;
precision highp int;
uniform sampler2D uRadiance;
uniform int uSamplesPerPixel;   // radiance texels per output pixel, along each axis
uniform bool uMapToDisplay;     // false: write the mean radiance and emitter fraction as they are
${TONE_MAP_GLSL}
layout(location = 0) out vec4 fragColor;
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 sum = vec4(0.0);
  for (int j = 0; j < uSamplesPerPixel; ++j)
    for (int i = 0; i < uSamplesPerPixel; ++i) sum += texelFetch(uRadiance, pixel * uSamplesPerPixel + ivec2(i, j), 0);
  vec4 mean = sum / float(uSamplesPerPixel * uSamplesPerPixel);
  fragColor = uMapToDisplay ? vec4(displayMapping(mean.rgb), 1.0) : mean;
}
`;

export class DisplayPass {
  constructor() {
    this.uniforms = {
      uRadiance: { value: null },
      uSamplesPerPixel: { value: 1 },
      uMapToDisplay: { value: true },
      ...toneUniforms(),
    };
    this.material = new THREE.ShaderMaterial({
      glslVersion: THREE.GLSL3,
      vertexShader,
      fragmentShader,
      uniforms: this.uniforms,
      depthTest: false,
      depthWrite: false,
    });
    this.quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.material);
    this.quad.frustumCulled = false;
    this.scene = new THREE.Scene();
    this.scene.add(this.quad);
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  }

  /** Display-mapped pixels of `radiance` (samplesPerPixel² texels each) into `target` (null: the canvas). */
  draw(renderer, radiance, samplesPerPixel, target, mapToDisplay = true) {
    this.uniforms.uRadiance.value = radiance.texture;
    this.uniforms.uSamplesPerPixel.value = samplesPerPixel;
    this.uniforms.uMapToDisplay.value = mapToDisplay;
    renderer.setRenderTarget(target);
    renderer.render(this.scene, this.camera);
    renderer.setRenderTarget(null);
  }
}
