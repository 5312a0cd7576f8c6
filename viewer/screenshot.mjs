// Makes docs/images/viewer-cornell.png, the viewer with its overlay on the
// Cornell box, the cursor on the back wall.
// Usage: node viewer/screenshot.mjs path/to/radiant [OUTPUT.png]
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { launchChromium, openViewer, requireBrowserDependencies, runRadiant, serveStatic } from '../tests/browser/harness.mjs';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const radiant = path.resolve(process.argv[2] ?? path.join(repo, 'build', 'radiant'));
const output = path.resolve(process.argv[3] ?? path.join(repo, 'docs', 'images', 'viewer-cornell.png'));
requireBrowserDependencies(repo);
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'radiant-screenshot-'));
const glb = path.join(work, 'box.glb');
runRadiant(radiant, ['export', path.join(repo, 'scenes', 'cornell-box', 'scene.json'), '-o', glb]);
const server = await serveStatic(path.join(repo, 'viewer'), { '/box.glb': glb });
const browser = await launchChromium(repo);
try {
  const viewer = await openViewer(browser, server.url, 'model=box.glb&tonemap=reinhard', 720, 480);
  await viewer.page.mouse.move(430, 200);
  await new Promise((resolve) => setTimeout(resolve, 1000));
  fs.writeFileSync(output, await viewer.page.screenshot({ type: 'png' }));
  console.log(`wrote ${output}`);
} finally {
  await browser.close();
  await server.close();
  fs.rmSync(work, { recursive: true, force: true });
}
