// `radiant export --lightmap` in a real browser (headless Chromium,
// SwiftShader), on the Cornell box (docs/export.md, "Lightmaps"):
//
//  1. the file passes the Khronos glTF validator with no error, is at most
//     2 MB, and has at most 4 triangles per input face (the scene's own
//     geometry, not the radiosity mesh);
//  2. the viewer shows it at the file's camera (`tonemap=linear&exposure=0`)
//     as `radiant render --method interpolate` shows the same solution:
//     mean luminance within 2 %, SSIM ≥ 0.95 (the lightmap holds the
//     solution as the display reads it);
//  3. and as a path-traced image of the scene shows it: mean within 3 %,
//     SSIM ≥ 0.93, so the block shadows are there (measured with 1024
//     samples: mean 0.993, SSIM 0.983; 512 keep the test at 25 s);
//  4. the same comparison rejects the view one stop too bright.
//
// Usage: node lightmap_test.mjs path/to/radiant SOURCE_DIR
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { checkList, decodePng, inViewer, requireBrowserDependencies, runRadiant, validateGltf } from './harness.mjs';
import { compareImages } from './image-compare.mjs';

const [radiant, repo] = process.argv.slice(2, 4).map((p) => path.resolve(p));
const SIZE = 256;
const PATH_SAMPLES = 512;

const { check, finish } = checkList();

async function main() {
  requireBrowserDependencies(repo);
  const work = fs.mkdtempSync(path.join(os.tmpdir(), 'radiant-lightmap-'));
  const scene = path.join(repo, 'scenes', 'cornell-box', 'scene.json');
  const solution = path.join(work, 'box.rad');
  const glb = path.join(work, 'box.glb');
  const interpolated = path.join(work, 'interpolate.png');
  const traced = path.join(work, 'path.png');
  const started = performance.now();
  runRadiant(radiant, ['solve', scene, '-o', solution]);
  const log = runRadiant(radiant, ['export', scene, '--solution', solution, '--lightmap', '-o', glb], { stdio: ['ignore', 'pipe', 'pipe'] });
  runRadiant(radiant, ['render', scene, '--method', 'interpolate', '--solution', solution, '--tonemap', 'linear',
    '--width', String(SIZE), '--height', String(SIZE), '-o', interpolated]);
  runRadiant(radiant, ['render', scene, '--method', 'path', '--spp', String(PATH_SAMPLES), '--tonemap', 'linear',
    '--width', String(SIZE), '--height', String(SIZE), '-q', '-o', traced]);
  console.log(`     radiant solve, export and renders: ${((performance.now() - started) / 1000).toFixed(1)} s${log ? `\n${log}` : ''}`);

  const report = await validateGltf(repo, glb);
  for (const line of report.lines) console.log(line);
  check(report.numErrors === 0, `gltf-validator ${report.version}: ${report.numErrors} errors, ${report.numWarnings} warnings, ${report.numInfos} infos`);
  const megabytes = fs.statSync(glb).size / 1e6;
  check(megabytes <= 2, `the .glb is ${megabytes.toFixed(2)} MB (at most 2)`);
  const json = JSON.parse(runRadiant(radiant, ['info', scene, '--json']));
  const glbJson = JSON.parse(glbJsonChunk(fs.readFileSync(glb)));
  const triangles = glbJson.meshes[0].primitives.reduce((n, p) => n + glbJson.accessors[p.indices].count / 3, 0);
  check(triangles <= 4 * json.faces, `${triangles} triangles for ${json.faces} input faces (at most 4 each)`);

  await inViewer(repo, { '/box.glb': glb }, work, SIZE, async ({ shoot }) => {
    const view = await shoot('model=box.glb&ui=0&tonemap=linear&exposure=0');
    check(view.title === 'ready', `the viewer loads the lightmapped export (title '${view.title}', ${view.loadSeconds.toFixed(1)} s)`);
    check(view.consoleErrors.length === 0, `no console error while loading${view.consoleErrors.map((e) => `\n       ${e}`).join('')}`);
    const display = compareImages(view.image, decodePng(fs.readFileSync(interpolated)));
    check(Math.abs(display.meanRatio - 1) <= 0.02 && display.ssim >= 0.95,
      `against radiant's interpolate display of the same solution: mean ratio ${display.meanRatio.toFixed(4)} (within 2 %), SSIM ${display.ssim.toFixed(4)} (≥ 0.95)`);
    const expected = decodePng(fs.readFileSync(traced));
    const truth = compareImages(view.image, expected);
    check(Math.abs(truth.meanRatio - 1) <= 0.03 && truth.ssim >= 0.93,
      `against path at ${PATH_SAMPLES} spp: mean ratio ${truth.meanRatio.toFixed(4)} (within 3 %), SSIM ${truth.ssim.toFixed(4)} (≥ 0.93)`);
    const bright = await shoot('model=box.glb&ui=0&tonemap=linear&exposure=1');
    const wrong = compareImages(bright.image, expected);
    check(Math.abs(wrong.meanRatio - 1) > 0.03, `exposure=1 is told apart: mean ratio ${wrong.meanRatio.toFixed(3)}`);
    if (process.env.RADIANT_VIEWER_TEST_KEEP) {
      fs.writeFileSync(path.join(process.env.RADIANT_VIEWER_TEST_KEEP, 'lightmap-viewer.png'), view.png);
      fs.copyFileSync(traced, path.join(process.env.RADIANT_VIEWER_TEST_KEEP, 'lightmap-path.png'));
      fs.copyFileSync(interpolated, path.join(process.env.RADIANT_VIEWER_TEST_KEEP, 'lightmap-interpolate.png'));
    }
  });
  finish();
}

/** The JSON chunk of a .glb (glTF 2.0 §4.4: a 12-byte header, then the chunk's length and type). */
function glbJsonChunk(bytes) {
  const length = bytes.readUInt32LE(12);
  return bytes.subarray(20, 20 + length).toString('utf8');
}

main().catch((error) => {
  console.error(`FAIL: ${error.message}`);
  process.exit(1);
});
