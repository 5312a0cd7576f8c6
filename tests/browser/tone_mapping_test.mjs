// The viewer's display mapping gives radiant's pixels, operator by operator.
//
// A radiance image with a wide range of levels and colours (W·sr⁻¹·m⁻²) is
// written as a PFM and mapped twice: by `radiant tonemap IMAGE --tonemap OP`
// into a PNG, and in headless Chromium by the viewer's own code — its
// statistics (statistics.js), operator constants (tone-operators.js) and
// display shader (display-pass.js) — into an 8-bit render target. Every
// channel of every pixel must agree within one 8-bit step (the shader works in
// 32-bit floats, radiant in doubles; a value on a rounding boundary may go
// either way).
//
// Usage: node tone_mapping_test.mjs path/to/radiant SOURCE_DIR
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { decodePng, launchChromium, requireBrowserDependencies, runRadiant, serveStatic } from './harness.mjs';

const [radiant, repo] = process.argv.slice(2).map((p) => path.resolve(p));
const WIDTH = 96;
const HEIGHT = 64;

// The cases: each operator with its defaults, and with the parameters the viewer lets the user change.
const CASES = [
  ['linear', {}],
  ['linear', { exposure: '-2.5' }],
  ['linear', { exposure: 'auto' }],
  ['linear', { exposure: 'auto', key: '0.3' }],
  ['max-reflected', {}],
  ['max-reflected', { 'reflected-level': '0.7' }],
  ['tumblin-rushmeier', {}],
  ['tumblin-rushmeier', { 'display-max': '200', 'display-contrast': '100', adaptation: '20' }],
  ['ward', {}],
  ['ward', { 'display-max': '250', adaptation: '5' }],
  ['reinhard', {}],
  ['reinhard', { key: '0.09', white: '300' }],
  ['aces', {}],
  ['aces', { key: '0.4' }],
];

/** Radiance, RGBA (A = 0: no emitter), rows bottom to top as a PFM and a GL texture store them. */
function radianceImage() {
  const rgba = new Float32Array(WIDTH * HEIGHT * 4);
  for (let y = 0; y < HEIGHT; ++y)
    for (let x = 0; x < WIDTH; ++x) {
      // Level: 10⁻⁴ … 10³ W·sr⁻¹·m⁻² along x; colour: a hue circle and a saturation ramp along y.
      const level = 10 ** (-4 + (7 * x) / (WIDTH - 1));
      const hue = (2 * Math.PI * (y % 16)) / 16;
      const saturation = Math.floor(y / 16) / 3;
      const c = [0, 1, 2].map((k) => level * (1 - saturation + saturation * (0.5 + 0.5 * Math.cos(hue - (2 * Math.PI * k) / 3))));
      const p = 4 * (y * WIDTH + x);
      rgba.set(y === 5 && x % 7 === 0 ? [0, 0, 0] : c, p); // some black pixels, left out of the log-average
    }
  return rgba;
}

function writePfm(file, rgba) {
  const header = Buffer.from(`PF\n${WIDTH} ${HEIGHT}\n-1.0\n`, 'latin1');
  const body = Buffer.alloc(WIDTH * HEIGHT * 12);
  for (let p = 0; p < WIDTH * HEIGHT; ++p) for (let c = 0; c < 3; ++c) body.writeFloatLE(rgba[4 * p + c], 12 * p + 4 * c);
  fs.writeFileSync(file, Buffer.concat([header, body]));
}

const PAGE = `<!doctype html><html><head><meta charset="utf-8"><title>loading</title><link rel="icon" href="data:,">
<script type="importmap">{"imports": {"three": "./node_modules/three/build/three.module.js"}}</script>
<script type="module">
import * as THREE from 'three';
import { DisplayPass } from './display-pass.js';
import { viewStatistics } from './statistics.js';
import { findToneOperator, setToneUniforms, toneParameters } from './tone-operators.js';
const renderer = new THREE.WebGLRenderer();
renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
renderer.toneMapping = THREE.NoToneMapping;
const pass = new DisplayPass();
// The viewer's path from a float image of radiance to 8-bit display values (rows bottom to top).
window.mapRadiance = (values, width, height, name, given) => {
  const pixels = Float32Array.from(values);
  const texture = new THREE.DataTexture(pixels, width, height, THREE.RGBAFormat, THREE.FloatType);
  texture.needsUpdate = true;
  const op = findToneOperator(name);
  const mapped = op.create(viewStatistics(pixels, width, height), toneParameters(op, given));
  setToneUniforms(pass.uniforms, mapped);
  const target = new THREE.WebGLRenderTarget(width, height, { type: THREE.UnsignedByteType });
  pass.draw(renderer, { texture }, 1, target);
  const out = new Uint8Array(width * height * 4);
  renderer.readRenderTargetPixels(target, 0, 0, width, height, out);
  target.dispose();
  texture.dispose();
  return { bytes: Array.from(out), describe: mapped.describe };
};
document.title = 'ready';
</script></head><body></body></html>`;

async function main() {
  requireBrowserDependencies(repo);
  const work = fs.mkdtempSync(path.join(os.tmpdir(), 'radiant-tone-'));
  const server = await serveStatic(path.join(repo, 'viewer'), { '/tone-test.html': path.join(work, 'tone-test.html') });
  fs.writeFileSync(path.join(work, 'tone-test.html'), PAGE);
  const browser = await launchChromium(repo);
  let failures = 0;
  try {
    const rgba = radianceImage();
    const pfm = path.join(work, 'ramp.pfm');
    writePfm(pfm, rgba);
    const page = await browser.newPage();
    const errors = [];
    page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}/tone-test.html`);
    await page.waitForFunction(() => document.title === 'ready', { timeout: 30000 });
    for (const [name, given] of CASES) {
      const png = path.join(work, 'mapped.png');
      const flags = Object.entries(given).flatMap(([k, v]) => [`--${k}`, v]);
      runRadiant(radiant, ['tonemap', pfm, '-o', png, '--tonemap', name, ...flags]);
      const expected = decodePng(fs.readFileSync(png));
      const { bytes, describe } = await page.evaluate((v, w, h, n, g) => window.mapRadiance(v, w, h, n, g), Array.from(rgba), WIDTH, HEIGHT, name, given);
      let largest = 0;
      let differing = 0;
      for (let y = 0; y < HEIGHT; ++y)
        for (let x = 0; x < WIDTH; ++x)
          for (let c = 0; c < 3; ++c) {
            const viewer = bytes[4 * (y * WIDTH + x) + c]; // bottom row first
            const reference = expected.rgb[3 * ((HEIGHT - 1 - y) * WIDTH + x) + c]; // PNG: top row first
            const d = Math.abs(viewer - reference);
            largest = Math.max(largest, d);
            if (d > 0) ++differing;
          }
      const label = `${name} ${JSON.stringify(given)}`;
      const ok = largest <= 1;
      if (!ok) ++failures;
      console.log(`${ok ? 'ok  ' : 'FAIL'} ${label}: largest difference ${largest}/255, ${differing} of ${WIDTH * HEIGHT * 3} values differ (${describe})`);
    }
    if (errors.length > 0) {
      ++failures;
      console.log(`FAIL console errors:\n  ${errors.join('\n  ')}`);
    }
  } finally {
    await browser.close();
    await server.close();
    fs.rmSync(work, { recursive: true, force: true });
  }
  if (failures > 0) {
    console.log(`${failures} failure(s)`);
    process.exit(1);
  }
  console.log(`all ${CASES.length} cases agree with radiant tonemap within 1/255`);
}

main().catch((error) => {
  console.error(`FAIL: ${error.message}`);
  process.exit(1);
});
