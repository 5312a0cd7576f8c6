// The viewer in a real browser (headless Chromium, SwiftShader, no GPU), on
// the Cornell box as `radiant export` writes it:
//
//  1. the export passes the Khronos glTF validator with no error (its
//     warnings and infos are listed);
//  2. the viewer loads it with no console error, and at the file's camera with
//     `ui=0&tonemap=linear&exposure=0` shows what
//     `radiant render --method interpolate --tonemap linear` shows of the same
//     solution at the same size: mean luminance within 2 %, SSIM of the
//     luminance ≥ 0.95 (image-compare.mjs);
//  3. the same comparison rejects the view one stop too bright (the test can
//     fail), and a missing model gives a clear error on the page.
//
// With a third argument, another scene of scenes/ (cornell-textured: the
// texture rule L = L_e + ρ(x)·H/π), only 1 and the linear comparison of 2.
//
// Usage: node viewer_test.mjs path/to/radiant SOURCE_DIR [SCENE]
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { checkList, decodePng, inViewer, openViewer, requireBrowserDependencies, runRadiant, validateGltf } from './harness.mjs';
import { compareImages } from './image-compare.mjs';

const [radiant, repo] = process.argv.slice(2, 4).map((p) => path.resolve(p));
const sceneName = process.argv[4] ?? 'cornell-box';
const full = sceneName === 'cornell-box';
const SIZE = 256;
const MEAN_TOLERANCE = 0.02;
const MIN_SSIM = 0.95;
// Operators that adapt to the view: the viewer takes their statistics from its own view, radiant from the
// image (the EXR, with its emitter channel); the same thresholds apply, but for tumblin-rushmeier: its
// curve is steep where the box is lit (I/k = L_d/L_dmax − 1/C_max with L_d ∝ L^1.26 at this adaptation),
// so the 0.7 % by which the two linear images differ (the viewer's triangles against radiant's bilinear
// quads, and 2 × 2 samples per pixel against 64 jittered ones) becomes about 3 % of its mean.
const MEAN_TOLERANCE_TUMBLIN_RUSHMEIER = 0.04;
const ADAPTIVE = [
  ['linear-auto', ['--tonemap', 'linear', '--exposure', 'auto'], 'tonemap=linear&exposure=auto'],
  ['max-reflected', ['--tonemap', 'max-reflected'], 'tonemap=max-reflected'],
  ['tumblin-rushmeier', ['--tonemap', 'tumblin-rushmeier'], 'tonemap=tumblin-rushmeier'],
  ['ward', ['--tonemap', 'ward'], 'tonemap=ward'],
  ['reinhard', ['--tonemap', 'reinhard'], 'tonemap=reinhard'],
  ['aces', ['--tonemap', 'aces'], 'tonemap=aces'],
];

const { check, finish } = checkList();

async function validate(file) {
  const report = await validateGltf(repo, file);
  for (const line of report.lines) console.log(line);
  check(report.numErrors === 0, `gltf-validator ${report.version}: ${report.numErrors} errors, ${report.numWarnings} warnings, ${report.numInfos} infos`);
}

/** The checks made on the Cornell box only: the adaptive operators, the readout, walking, the test's power, errors. */
async function fullChecks(shoot, browser, baseUrl, work, expected) {
  for (const [name, , query] of ADAPTIVE) {
    const view = await shoot(`model=box.glb&ui=0&${query}`);
    const c = compareImages(view.image, decodePng(fs.readFileSync(path.join(work, `box-${name}.png`))));
    check(
      Math.abs(c.meanRatio - 1) <= (name === 'tumblin-rushmeier' ? MEAN_TOLERANCE_TUMBLIN_RUSHMEIER : MEAN_TOLERANCE) && c.ssim >= MIN_SSIM && view.consoleErrors.length === 0,
      `${query}: mean ratio ${c.meanRatio.toFixed(4)}, SSIM ${c.ssim.toFixed(4)}${view.consoleErrors.map((e) => `\n       ${e}`).join('')}`,
    );
  }

  // Under the cursor: on the back wall (white, untextured, no emission) L = ρH/π per channel, as at every
  // mesh node (B = E + ρH), and the readouts are 683 × Y of L and of H.
  const walk = await openViewer(browser, baseUrl, 'model=box.glb&tonemap=linear&ui=0', SIZE, SIZE);
  await walk.page.mouse.move(SIZE / 2, SIZE / 3);
  await walk.page.waitForFunction(() => window.radiantViewer.lastPick !== undefined, { timeout: 10000 });
  const pick = await walk.page.evaluate(() => ({
    ...window.radiantViewer.lastPick,
    luminance: document.getElementById('luminance').textContent,
    illuminance: document.getElementById('illuminance').textContent,
  }));
  const white = [0.885809, 0.698859, 0.666422];
  const worst = Math.max(...[0, 1, 2].map((c) => Math.abs(pick.radiance[c] / ((white[c] * pick.irradiance[c]) / Math.PI) - 1)));
  const y = (v) => 683 * (0.212639 * v[0] + 0.7151687 * v[1] + 0.0721923 * v[2]);
  check(
    worst < 1e-3 && Math.abs(parseFloat(pick.luminance) / y(pick.radiance) - 1) < 0.01 && Math.abs(parseFloat(pick.illuminance) / y(pick.irradiance) - 1) < 0.01,
    `readout on the back wall: ${pick.luminance}, ${pick.illuminance}; L = ρH/π within ${(worst * 100).toFixed(3)} %`,
  );
  // Walking: W moves the camera forward (+z, the file's camera looks down the box), a drag turns it.
  const before = await walk.page.evaluate(() => window.radiantViewer.camera.position.z);
  await walk.page.keyboard.down('KeyW');
  await new Promise((resolve) => setTimeout(resolve, 400));
  await walk.page.keyboard.up('KeyW');
  await walk.page.mouse.down();
  await walk.page.mouse.move(SIZE / 2 + 40, SIZE / 3, { steps: 4 });
  await walk.page.mouse.up();
  const after = await walk.page.evaluate(() => ({ z: window.radiantViewer.camera.position.z, yaw: window.radiantViewer.controls.yaw }));
  check(after.z > before + 0.01 && after.yaw < 0, `W walks forward (z ${before.toFixed(3)} → ${after.z.toFixed(3)} m), a drag turns (yaw ${after.yaw.toFixed(3)} rad)`);
  check(walk.consoleErrors.length === 0, `no console error while walking${walk.consoleErrors.map((e) => `\n       ${e}`).join('')}`);
  await walk.page.close();

  // The comparison has power: one stop too bright must fail it.
  const bright = await shoot('model=box.glb&ui=0&tonemap=linear&exposure=1');
  const wrong = compareImages(bright.image, expected);
  check(Math.abs(wrong.meanRatio - 1) > MEAN_TOLERANCE, `exposure=1 is told apart: mean ratio ${wrong.meanRatio.toFixed(3)}, SSIM ${wrong.ssim.toFixed(3)}`);

  const missing = await openViewer(browser, baseUrl, 'model=no-such-file.glb', SIZE, SIZE);
  const shown = await missing.page.$eval('#error', (e) => (e.hidden ? '' : e.textContent));
  check(/404/.test(shown), `a missing model is reported on the page: '${shown}'`);
  await missing.page.close();
}

/** `radiant serve` (the viewer's folder and the model at /model.glb) shows the same pixels as the test's server. */
async function serveCheck(browser, glb, expectedImage) {
  const server = spawn(radiant, ['serve', glb, '--port', '0'], { stdio: ['ignore', 'pipe', 'ignore'] });
  try {
    const address = await new Promise((resolve, reject) => {
      let out = '';
      server.stdout.on('data', (data) => {
        out += data;
        const match = /(http:\/\/[^\s]+)\/index\.html/.exec(out);
        if (match) resolve(match[1]);
      });
      server.on('exit', (code) => reject(new Error(`radiant serve exited (${code}) before printing its address`)));
      setTimeout(() => reject(new Error('radiant serve printed no address in 10 s')), 10000);
    });
    const viewer = await openViewer(browser, address, 'model=model.glb&ui=0&tonemap=linear&exposure=0', SIZE, SIZE);
    const image = decodePng(Buffer.from(await viewer.page.screenshot({ type: 'png' })));
    await viewer.page.close();
    const same = image.rgb.every((v, i) => v === expectedImage.rgb[i]);
    check(viewer.title === 'ready' && viewer.consoleErrors.length === 0 && same,
      `through radiant serve (${address}): '${viewer.title}', ${viewer.consoleErrors.length} console errors, ${same ? 'the same pixels' : 'other pixels'}`);
  } finally {
    server.kill();
  }
}

async function main() {
  requireBrowserDependencies(repo);
  const work = fs.mkdtempSync(path.join(os.tmpdir(), 'radiant-viewer-'));
  const scene = path.join(repo, 'scenes', sceneName, 'scene.json');
  const solution = path.join(work, 'box.rad');
  const glb = path.join(work, 'box.glb');
  const reference = path.join(work, 'box.png');
  const referenceExr = path.join(work, 'box.exr');
  const started = performance.now();
  // One solution for both, so that the comparison is of display, not of two solves.
  runRadiant(radiant, ['solve', scene, '-o', solution]);
  runRadiant(radiant, ['export', scene, '--solution', solution, '-o', glb]);
  runRadiant(radiant, ['render', scene, '--method', 'interpolate', '--solution', solution, '--tonemap', 'linear',
    '--width', String(SIZE), '--height', String(SIZE), '-o', reference, '-o', referenceExr]);
  if (full)
    for (const [name] of ADAPTIVE)
      runRadiant(radiant, ['tonemap', referenceExr, '-o', path.join(work, `box-${name}.png`), ...ADAPTIVE.find((a) => a[0] === name)[1]]);
  console.log(`     radiant solve, export and render: ${((performance.now() - started) / 1000).toFixed(1)} s`);

  await validate(glb);

  await inViewer(repo, { '/box.glb': glb }, work, SIZE, async ({ browser, server, shoot }) => {
    const expected = decodePng(fs.readFileSync(reference));

    const linear = await shoot('model=box.glb&ui=0&tonemap=linear&exposure=0');
    check(linear.title === 'ready', `the viewer loads the export (title '${linear.title}', ${linear.loadSeconds.toFixed(1)} s)`);
    check(linear.consoleErrors.length === 0, `no console error while loading${linear.consoleErrors.map((e) => `\n       ${e}`).join('')}`);
    const same = compareImages(linear.image, expected);
    check(Math.abs(same.meanRatio - 1) <= MEAN_TOLERANCE, `mean luminance viewer / radiant render = ${same.meanRatio.toFixed(4)} (within ${MEAN_TOLERANCE * 100} %)`);
    check(same.ssim >= MIN_SSIM, `SSIM of the luminance = ${same.ssim.toFixed(4)} (≥ ${MIN_SSIM})`);
    if (process.env.RADIANT_VIEWER_TEST_KEEP) {
      fs.writeFileSync(path.join(process.env.RADIANT_VIEWER_TEST_KEEP, 'viewer.png'), linear.png);
      fs.copyFileSync(reference, path.join(process.env.RADIANT_VIEWER_TEST_KEEP, 'radiant.png'));
    }

    if (full) {
      await fullChecks(shoot, browser, server.url, work, expected);
      await serveCheck(browser, glb, linear.image);
    }
  });
  finish();
}

main().catch((error) => {
  console.error(`FAIL: ${error.message}`);
  process.exit(1);
});
