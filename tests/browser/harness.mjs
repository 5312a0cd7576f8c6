// What the browser tests (tests/browser/) and the viewer benchmark
// (bench/viewer/) share: the check that Chromium and the viewer's npm packages
// are installed, a static server for the viewer and the models, headless
// Chromium through puppeteer-core, a PNG decoder, and luminance images.
//
// No package beyond viewer/package.json's: PNGs are decoded with node's zlib.
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import http from 'node:http';
import { createRequire } from 'node:module';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import zlib from 'node:zlib';

export const CHROMIUM = process.env.RADIANT_CHROMIUM ?? '/usr/bin/chromium';

/** Fails (never skips) when something the browser tests need is missing, saying how to install it. */
export function requireBrowserDependencies(repo) {
  const missing = [];
  if (!fs.existsSync(CHROMIUM)) missing.push(`Chromium (${CHROMIUM})`);
  for (const name of ['three', 'puppeteer-core', 'gltf-validator'])
    if (!fs.existsSync(path.join(repo, 'viewer', 'node_modules', name, 'package.json'))) missing.push(`viewer/node_modules/${name}`);
  if (missing.length === 0) return;
  const message = `missing ${missing.join(', ')}: run scripts/install-deps.sh (it installs chromium and runs npm ci in viewer/)`;
  // CI (.ci/run) requires these tests; elsewhere a machine that cannot reach the npm registry reports them
  // skipped (exit 77, ctest's SKIP_RETURN_CODE), loudly, instead of failing the whole suite.
  if (process.env.RADIANT_REQUIRE_BROWSER_TESTS === '1') throw new Error(message);
  console.log(`SKIPPED: ${message}`);
  process.exit(77);
}

/** A package of viewer/node_modules, imported from outside viewer/. */
export async function importViewerPackage(repo, name) {
  const require = createRequire(path.join(repo, 'viewer', 'package.json'));
  return import(pathToFileURL(require.resolve(name)).href);
}

const MIME = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.glb': 'model/gltf-binary',
  '.gltf': 'model/gltf+json',
  '.bin': 'application/octet-stream',
  '.png': 'image/png',
  '.jpg': 'image/jpeg',
  '.jpeg': 'image/jpeg',
};

/**
 * Serves `root` (the viewer folder) on 127.0.0.1 at a random port; `extra`
 * maps URL paths ("/box.glb") to files elsewhere. Resolves to {url, close}.
 */
export function serveStatic(root, extra = {}) {
  const server = http.createServer((request, response) => {
    const urlPath = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    let file = extra[urlPath];
    if (!file) {
      file = path.join(root, path.normalize(urlPath === '/' ? '/index.html' : urlPath));
      if (!file.startsWith(path.resolve(root))) file = null;
    }
    fs.readFile(file ?? '', (error, data) => {
      if (error) {
        response.writeHead(404, { 'Content-Type': 'text/plain' });
        response.end('not found');
        return;
      }
      response.writeHead(200, { 'Content-Type': MIME[path.extname(file).toLowerCase()] ?? 'application/octet-stream' });
      response.end(data);
    });
  });
  return new Promise((resolve) => {
    server.listen(0, '127.0.0.1', () => {
      resolve({ url: `http://127.0.0.1:${server.address().port}`, close: () => new Promise((r) => server.close(r)) });
    });
  });
}

/** Headless Chromium without a GPU (SwiftShader), as in CI; never downloads a browser. */
export async function launchChromium(repo) {
  const { default: puppeteer } = await importViewerPackage(repo, 'puppeteer-core');
  return puppeteer.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: [
      '--headless',
      '--no-sandbox', // CI runs as root
      '--use-angle=swiftshader',
      '--enable-unsafe-swiftshader',
      '--force-color-profile=srgb', // the screenshot's bytes are the canvas's, unconverted
      '--ignore-gpu-blocklist',
    ],
  });
}

/**
 * Opens the viewer at `query` in a width × height page (device scale factor 1)
 * and waits until its title says "ready" or "error: …". Resolves to
 * {page, title, consoleErrors, loadSeconds}.
 */
export async function openViewer(browser, baseUrl, query, width, height, timeoutMs = 45000) {
  const page = await browser.newPage();
  const consoleErrors = [];
  page.on('console', (message) => {
    if (message.type() === 'error' && !/favicon\.ico/.test(message.location()?.url ?? '')) consoleErrors.push(message.text());
  });
  page.on('pageerror', (error) => consoleErrors.push(`page error: ${error.message}`));
  page.on('requestfailed', (request) => consoleErrors.push(`request failed: ${request.url()}`));
  await page.setViewport({ width, height, deviceScaleFactor: 1 });
  const start = performance.now();
  await page.goto(`${baseUrl}/index.html?${query}`, { waitUntil: 'load' });
  await page.waitForFunction(() => document.title === 'ready' || document.title.startsWith('error'), { timeout: timeoutMs, polling: 50 });
  const loadSeconds = (performance.now() - start) / 1000;
  return { page, title: await page.title(), consoleErrors, loadSeconds };
}

/** Decodes an 8-bit, non-interlaced RGB or RGBA PNG: {width, height, rgb: Uint8Array (3 per pixel)}. */
export function decodePng(buffer) {
  if (buffer.readUInt32BE(0) !== 0x89504e47) throw new Error('not a PNG');
  let offset = 8;
  let width = 0;
  let height = 0;
  let colourType = 0;
  const idat = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('latin1', offset + 4, offset + 8);
    const data = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      const bitDepth = data[8];
      colourType = data[9];
      if (bitDepth !== 8 || (colourType !== 2 && colourType !== 6) || data[12] !== 0)
        throw new Error(`PNG: only 8-bit non-interlaced RGB(A) is supported (depth ${bitDepth}, colour type ${colourType})`);
    } else if (type === 'IDAT') idat.push(data);
    else if (type === 'IEND') break;
    offset += 12 + length;
  }
  const channels = colourType === 6 ? 4 : 3;
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const pixels = new Uint8Array(height * stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? pixels[y * stride + i - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + i] : 0;
      const c = y > 0 && i >= channels ? pixels[(y - 1) * stride + i - channels] : 0;
      let predictor = 0;
      if (filter === 1) predictor = a;
      else if (filter === 2) predictor = b;
      else if (filter === 3) predictor = (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c;
        const pa = Math.abs(p - a);
        const pb = Math.abs(p - b);
        const pc = Math.abs(p - c);
        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      } else if (filter !== 0) throw new Error(`PNG: unknown filter ${filter}`);
      pixels[y * stride + i] = (line[i] + predictor) & 255;
    }
  }
  const rgb = new Uint8Array(width * height * 3);
  for (let p = 0; p < width * height; ++p) for (let c = 0; c < 3; ++c) rgb[3 * p + c] = pixels[channels * p + c];
  return { width, height, rgb };
}

const srgbDecode = (v) => (v <= 0.04045 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4);
const DECODE = Float64Array.from({ length: 256 }, (_, i) => srgbDecode(i / 255));

/** Relative luminance (linear, 0…1) of every pixel of an sRGB-encoded 8-bit image. */
export function linearLuminance(image) {
  const y = new Float64Array(image.width * image.height);
  for (let p = 0; p < y.length; ++p)
    y[p] = 0.212639 * DECODE[image.rgb[3 * p]] + 0.7151687 * DECODE[image.rgb[3 * p + 1]] + 0.0721923 * DECODE[image.rgb[3 * p + 2]];
  return y;
}

/** Runs radiant with `args`; throws with its output when it fails. */
export function runRadiant(radiant, args, options = {}) {
  try {
    return execFileSync(radiant, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'], ...options });
  } catch (error) {
    throw new Error(`radiant ${args.join(' ')} failed (${error.status}):\n${error.stdout ?? ''}${error.stderr ?? ''}`);
  }
}

/**
 * The Khronos glTF validator's report on a file (its external resources read beside it), and its lines to print:
 * errors, warnings and infos.
 */
export async function validateGltf(repo, file) {
  const { default: validator } = await importViewerPackage(repo, 'gltf-validator');
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) => Promise.resolve(new Uint8Array(fs.readFileSync(path.join(path.dirname(file), decodeURIComponent(uri))))),
  });
  const { numErrors, numWarnings, numInfos, messages } = report.issues;
  const lines = [];
  for (const m of messages) if (m.severity > 0) lines.push(`     ${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  for (const m of messages) if (m.severity === 0) lines.push(`     error ${m.code} ${m.pointer ?? ''}: ${m.message}`);
  return { numErrors, numWarnings, numInfos, lines, version: validator.version() };
}

/** A browser test's checks: each printed "ok" or "FAIL", counted, and the exit status they make. */
export function checkList() {
  let failures = 0;
  return {
    check(ok, message) {
      console.log(`${ok ? 'ok  ' : 'FAIL'} ${message}`);
      if (!ok) ++failures;
    },
    /** Ends the process: 1 when any check failed. */
    finish() {
      if (failures > 0) {
        console.log(`${failures} check(s) failed`);
        process.exit(1);
      }
      console.log('all checks passed');
    },
  };
}

/** A screenshot of the viewer at `query` (size × size), decoded, with the page's title, errors and load time. */
export function viewerShooter(browser, baseUrl, size) {
  return async (query) => {
    const viewer = await openViewer(browser, baseUrl, query, size, size);
    const png = await viewer.page.screenshot({ type: 'png' });
    await viewer.page.close();
    return { ...viewer, image: decodePng(Buffer.from(png)), png };
  };
}

/**
 * Serves viewer/ with `routes` (URL path → file), opens Chromium, and runs `body({ browser, server, shoot })`
 * (shoot: viewerShooter at size × size); prints the browser's time, then closes both and removes `work`.
 */
export async function inViewer(repo, routes, work, size, body) {
  const server = await serveStatic(path.join(repo, 'viewer'), routes);
  const browser = await launchChromium(repo);
  try {
    const started = performance.now();
    await body({ browser, server, shoot: viewerShooter(browser, server.url, size) });
    console.log(`     browser: ${((performance.now() - started) / 1000).toFixed(1)} s`);
  } finally {
    await browser.close();
    await server.close();
    fs.rmSync(work, { recursive: true, force: true });
  }
}
