// The viewer's speed in headless Chromium (SwiftShader: the CPU draws, so
// these are a floor; a GPU is far faster): how long a large export takes to
// load (page open → first frame with the view's statistics, `document.title`
// "ready"), and frames per second while walking (W held, the camera turning
// slowly, for a few seconds) with each tone operator kind. A program, not a
// test: it prints a table of medians over several runs.
//
// Usage: node bench/viewer/viewer_bench.mjs MODEL.glb [--runs 3] [--seconds 5] [--size 640x480]
//   e.g. build/radiant export scenes/cornell-sphere-1m/scene.json -o sphere.glb
//        node bench/viewer/viewer_bench.mjs sphere.glb
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, openViewer, requireBrowserDependencies, serveStatic } from '../../tests/browser/harness.mjs';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..', '..');

function options(argv) {
  const o = { model: null, runs: 3, seconds: 5, width: 640, height: 480 };
  for (let i = 0; i < argv.length; ++i) {
    if (argv[i] === '--runs') o.runs = Number(argv[++i]);
    else if (argv[i] === '--seconds') o.seconds = Number(argv[++i]);
    else if (argv[i] === '--size') [o.width, o.height] = argv[++i].split('x').map(Number);
    else o.model = argv[i];
  }
  if (!o.model) throw new Error('usage: viewer_bench.mjs MODEL.glb [--runs N] [--seconds S] [--size WxH]');
  return o;
}

const median = (values) => {
  const s = [...values].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

/** Frames drawn while walking forward and turning for `seconds`, per second. */
async function walkingFrameRate(page, seconds) {
  await page.keyboard.down('KeyW');
  const result = await page.evaluate(async (ms) => {
    const viewer = window.radiantViewer;
    const startFrames = viewer.frameCount;
    const start = performance.now();
    // Turn a little every animation frame, as a mouse drag would.
    await new Promise((resolve) => {
      const step = () => {
        viewer.controls.yaw += 0.002;
        viewer.controls.applyOrientation();
        viewer.viewChanged();
        if (performance.now() - start < ms) requestAnimationFrame(step);
        else resolve();
      };
      requestAnimationFrame(step);
    });
    return { frames: viewer.frameCount - startFrames, seconds: (performance.now() - start) / 1000 };
  }, seconds * 1000);
  await page.keyboard.up('KeyW');
  return result.frames / result.seconds;
}

async function main() {
  const o = options(process.argv.slice(2));
  requireBrowserDependencies(repo);
  const model = path.resolve(o.model);
  const json = JSON.parse(readGlbJson(model));
  const triangles = json.meshes
    .flatMap((m) => m.primitives)
    .reduce((n, p) => n + (p.indices !== undefined ? json.accessors[p.indices].count : json.accessors[p.attributes.POSITION].count) / 3, 0);
  const server = await serveStatic(path.join(repo, 'viewer'), { '/model.glb': model });
  const browser = await launchChromium(repo);
  const rows = [];
  try {
    const cases = [
      ['linear, 2×2 samples/pixel', 'tonemap=linear&exposure=0'],
      ['linear, 1 sample/pixel', 'tonemap=linear&exposure=0&ss=1'],
      ['reinhard (adaptive), 2×2', 'tonemap=reinhard'],
    ];
    for (const [label, query] of cases) {
      const loads = [];
      const rates = [];
      for (let run = 0; run < o.runs; ++run) {
        const viewer = await openViewer(browser, server.url, `model=model.glb&ui=0&${query}`, o.width, o.height, 600000);
        if (viewer.title !== 'ready') throw new Error(`the viewer says '${viewer.title}'`);
        loads.push(viewer.loadSeconds);
        rates.push(await walkingFrameRate(viewer.page, o.seconds));
        await viewer.page.close();
      }
      rows.push({ label, load: median(loads), fps: median(rates), loads, rates });
    }
  } finally {
    await browser.close();
    await server.close();
  }
  const size = fs.statSync(model).size / 2 ** 20;
  console.log(`viewer benchmark: ${path.basename(model)}, ${triangles.toLocaleString('en')} triangles, ${size.toFixed(1)} MiB;`);
  console.log(`headless Chromium (SwiftShader), ${o.width}×${o.height}, ${os.cpus().length} CPUs; medians of ${o.runs} runs (each run in brackets)`);
  console.log('| operator | load to first final frame (s) | frames/s walking |');
  console.log('|---|---|---|');
  for (const r of rows)
    console.log(`| ${r.label} | ${r.load.toFixed(2)} (${r.loads.map((x) => x.toFixed(2)).join(', ')}) | ${r.fps.toFixed(2)} (${r.rates.map((x) => x.toFixed(2)).join(', ')}) |`);
}

/** The JSON chunk of a .glb (only it is read), or a .gltf's text. */
function readGlbJson(file) {
  const fd = fs.openSync(file, 'r');
  try {
    const header = Buffer.alloc(20);
    fs.readSync(fd, header, 0, 20, 0);
    if (header.readUInt32LE(0) !== 0x46546c67) return fs.readFileSync(file, 'utf8');
    const json = Buffer.alloc(header.readUInt32LE(12));
    fs.readSync(fd, json, 0, json.length, 20);
    return json.toString('utf8');
  } finally {
    fs.closeSync(fd);
  }
}

main().catch((error) => {
  console.error(`viewer_bench: ${error.message}`);
  process.exit(1);
});
