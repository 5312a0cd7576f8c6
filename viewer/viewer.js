// Radiant's viewer: loads a .glb from `radiant export` (docs/export.md; with
// --lightmap, the light read from the lightmap: lightmap-material.js),
// draws its radiance into a float target, and shows it with radiant's display
// mapping, the tone operator adapted to the current view (viewer/README.md).
//
// URL parameters: model= (a URL relative to the page), camera=N (default 0),
// tonemap= (radiant's operator names), exposure= (stops or auto) and the other
// operators' parameters under their radiant names (key=, reflected-level=,
// display-max=, display-contrast=, adaptation=, white=), ss= (samples per pixel
// along each axis, default 2), ui=0 (no overlay).
//
// `document.title` becomes "ready" once a frame has been drawn with the
// statistics of its own view (the tests wait for it), "error: …" on failure.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { DisplayPass } from './display-pass.js';
import { Overlay, showError } from './overlay.js';
import { createLightmapMaterial, lightmapOf } from './lightmap-material.js';
import { OUTPUT_IRRADIANCE, OUTPUT_RADIANCE, createRadianceMaterial } from './radiance-material.js';
import { viewStatistics } from './statistics.js';
import {
  LUMINOUS_EFFICACY,
  TONE_OPERATORS,
  findToneOperator,
  relativeLuminance,
  setToneUniforms,
  toneParameters,
} from './tone-operators.js';
import { WalkControls } from './walk-controls.js';

// Statistics are read back at most this often while the view changes, and once more when it stops.
const STATISTICS_INTERVAL_MS = 250;
// Above this many pixels the statistics are taken from a view averaged down by an integer factor.
const STATISTICS_MAX_PIXELS = 512 * 512;
const MAX_RADIANCE_SAMPLES = 16 * 1024 * 1024;

const query = new URLSearchParams(window.location.search);

function readSettings() {
  const operator = query.get('tonemap') ?? 'linear';
  // Every operator's parameters under their radiant names, kept as given and checked now, as radiant checks its flags.
  const known = new Set(['model', 'camera', 'tonemap', 'ui', 'ss']);
  const parameters = {};
  for (const o of TONE_OPERATORS)
    for (const spec of o.parameters) {
      known.add(spec.name);
      if (query.has(spec.name)) parameters[spec.name] = query.get(spec.name);
    }
  for (const name of query.keys()) if (!known.has(name)) throw new Error(`unknown URL parameter '${name}'`);
  for (const o of TONE_OPERATORS) toneParameters(o, parameters);
  findToneOperator(operator);
  const samples = Number(query.get('ss') ?? 2);
  if (!Number.isInteger(samples) || samples < 1 || samples > 4) throw new Error(`ss: expected 1 to 4, got '${query.get('ss')}'`);
  const camera = Number(query.get('camera') ?? 0);
  if (!Number.isInteger(camera) || camera < 0) throw new Error(`camera: expected a camera index, got '${query.get('camera')}'`);
  return { operator, parameters, samplesPerPixel: samples, cameraIndex: camera, ui: query.get('ui') !== '0' };
}

async function loadModel(url) {
  const loader = new GLTFLoader();
  let gltf;
  try {
    gltf = await loader.loadAsync(url);
  } catch (error) {
    const reason = error?.target?.status ? `HTTP ${error.target.status} ${error.target.statusText}` : (error?.message ?? String(error));
    throw new Error(`cannot load the model '${url}': ${reason}`);
  }
  const json = gltf.parser.json;
  const meshes = [];
  gltf.scene.traverse((object) => object.isMesh && meshes.push(object));
  if (meshes.length === 0) throw new Error(`'${url}' holds no mesh`);
  const lightmapped = json.extensionsUsed?.includes('RADIANT_lightmap');
  for (const object of meshes) {
    const geometry = object.geometry;
    const index = gltf.parser.associations.get(object.material)?.materials;
    const materialDef = index !== undefined ? json.materials[index] : undefined;
    const lightmap = lightmapOf(materialDef);
    // The shaders read only these; COLOR_0 (for plain viewers) and NORMAL would take GPU memory for nothing.
    geometry.deleteAttribute('color');
    geometry.deleteAttribute('normal');
    if (lightmap) {
      // docs/export.md "Lightmaps": the light on TEXCOORD_1, the material's own colour in the extension.
      if (!geometry.getAttribute('uv1'))
        throw new Error(`'${url}': mesh '${object.name}' has a RADIANT_lightmap material but no TEXCOORD_1`);
      const irradiance = await gltf.parser.getDependency('texture', lightmap.irradianceTexture.index);
      const base = lightmap.baseColorTexture ? await gltf.parser.getDependency('texture', lightmap.baseColorTexture.index) : null;
      object.material = createLightmapMaterial(materialDef, irradiance, base);
      continue;
    }
    if (!geometry.getAttribute('_radiance')) {
      // A lightmapped file's mirrors and glass carry no light of their own (docs/export.md): black, as in the solution.
      if (!lightmapped)
        throw new Error(`'${url}' is not a radiant export: mesh '${object.name}' has no _RADIANCE attribute (docs/export.md)`);
      geometry.setAttribute('_radiance', new THREE.BufferAttribute(new Float32Array(3 * geometry.getAttribute('position').count), 3));
    }
    if (!geometry.getAttribute('_irradiance')) {
      const count = geometry.getAttribute('position').count;
      geometry.setAttribute('_irradiance', new THREE.BufferAttribute(new Float32Array(3 * count), 3));
    }
    object.material = createRadianceMaterial(materialDef, object.material);
  }
  return gltf;
}

/** The camera to start from: the file's camera N, as a world-space PerspectiveCamera. */
function startingCamera(gltf, index, sceneSize) {
  const cameras = gltf.cameras ?? [];
  const camera = new THREE.PerspectiveCamera(50, 1, sceneSize * 1e-3, sceneSize * 100);
  if (cameras.length === 0) {
    if (index !== 0) throw new Error(`camera=${index}: the file has no camera`);
    // No camera: look at the scene from the front of its bounding box.
    const box = new THREE.Box3().setFromObject(gltf.scene);
    const centre = box.getCenter(new THREE.Vector3());
    camera.position.copy(centre).add(new THREE.Vector3(0, 0, sceneSize));
    camera.lookAt(centre);
    return camera;
  }
  if (index >= cameras.length) throw new Error(`camera=${index}: the file has ${cameras.length} camera(s), 0 to ${cameras.length - 1}`);
  const source = cameras[index];
  if (!source.isPerspectiveCamera) throw new Error(`camera=${index} is not a perspective camera`);
  gltf.scene.updateMatrixWorld(true);
  source.updateMatrixWorld(true);
  source.matrixWorld.decompose(camera.position, camera.quaternion, new THREE.Vector3());
  camera.fov = source.fov; // yfov, degrees
  camera.near = Math.min(source.near > 0 ? source.near : camera.near, camera.near);
  camera.updateMatrixWorld();
  return camera;
}

class Viewer {
  constructor(gltf, settings) {
    this.settings = settings;
    this.canvas = document.getElementById('view');
    // The shader writes the final encoded value: no tone mapping or colour-space conversion by three.
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: false, alpha: false, preserveDrawingBuffer: true });
    this.renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    this.renderer.toneMapping = THREE.NoToneMapping;
    this.renderer.setClearColor(0x000000, 0);
    this.renderer.setPixelRatio(window.devicePixelRatio);

    this.scene = gltf.scene;
    const box = new THREE.Box3().setFromObject(this.scene);
    this.sceneSize = box.isEmpty() ? 1 : box.getSize(new THREE.Vector3()).length();
    this.camera = startingCamera(gltf, settings.cameraIndex, this.sceneSize);
    this.materials = [];
    this.scene.traverse((o) => o.isMesh && this.materials.push(o.material));

    this.display = new DisplayPass();
    const floatTarget = () =>
      new THREE.WebGLRenderTarget(1, 1, {
        type: THREE.FloatType,
        format: THREE.RGBAFormat,
        minFilter: THREE.NearestFilter,
        magFilter: THREE.NearestFilter,
        depthBuffer: true,
        colorSpace: THREE.NoColorSpace,
      });
    this.radiance = floatTarget();
    this.statisticsTarget = floatTarget();
    this.pickTarget = floatTarget();

    this.controls = new WalkControls(this.camera, this.canvas, this.sceneSize);
    this.controls.onChange = () => this.viewChanged();
    this.overlay = new Overlay(settings, settings.ui, () => this.settingsChanged());

    this.frameCount = 0;
    this.statistics = null;
    this.statisticsStale = true;
    this.statisticsTime = -Infinity;
    this.needsDraw = true;
    this.ready = false;
    this.cursor = null;
    this.frameTimes = [];

    this.canvas.addEventListener('pointermove', (e) => {
      this.cursor = { x: e.offsetX, y: e.offsetY };
      this.pickStale = true;
    });
    this.canvas.addEventListener('pointerleave', () => {
      this.cursor = null;
      this.overlay.readout(NaN, NaN);
    });
    window.addEventListener('resize', () => this.resize());
    this.resize();
    this.lastTime = performance.now();
    this.renderer.setAnimationLoop((time) => this.frame(time));
  }

  get operator() {
    return findToneOperator(this.settings.operator);
  }

  resize() {
    this.renderer.setSize(window.innerWidth, window.innerHeight, false);
    const size = this.renderer.getDrawingBufferSize(new THREE.Vector2());
    this.width = size.x;
    this.height = size.y;
    this.camera.aspect = this.width / this.height; // yfov kept, the width follows the window
    this.camera.updateProjectionMatrix();
    // ss × ss samples per pixel, fewer on a large window: 16 M float samples (256 MiB) at most, and no side
    // beyond the GPU's limit.
    const limit = this.renderer.capabilities.maxTextureSize;
    let s = this.settings.samplesPerPixel;
    while (s > 1 && (this.width * this.height * s * s > MAX_RADIANCE_SAMPLES || Math.max(this.width, this.height) * s > limit)) --s;
    this.samplesPerPixel = s;
    this.radiance.setSize(this.width * s, this.height * s);
    this.statisticsReduction = Math.max(1, Math.ceil(Math.sqrt((this.width * this.height) / STATISTICS_MAX_PIXELS)));
    this.statisticsTarget.setSize(Math.floor(this.width / this.statisticsReduction), Math.floor(this.height / this.statisticsReduction));
    this.viewChanged();
  }

  viewChanged() {
    this.needsDraw = true;
    this.statisticsStale = true;
    this.pickStale = true;
  }

  settingsChanged() {
    this.needsDraw = true;
    this.statisticsStale = this.statisticsStale || this.statistics === null;
  }

  setOutput(output) {
    for (const m of this.materials) m.uniforms.uOutput.value = output;
  }

  renderRadiance(target) {
    this.setOutput(OUTPUT_RADIANCE);
    this.renderer.setRenderTarget(target);
    this.renderer.clear();
    this.renderer.render(this.scene, this.camera);
    this.renderer.setRenderTarget(null);
  }

  /** The view's per-pixel mean radiance and emitter fraction, read back: what radiant's operators read from an image. */
  readStatistics() {
    const target = this.statisticsTarget;
    this.display.draw(this.renderer, this.radiance, this.samplesPerPixel * this.statisticsReduction, target, false);
    const pixels = new Float32Array(target.width * target.height * 4);
    this.renderer.readRenderTargetPixels(target, 0, 0, target.width, target.height, pixels);
    this.statistics = viewStatistics(pixels, target.width, target.height);
    this.statisticsStale = false;
    this.statisticsTime = performance.now();
  }

  /** Radiance and irradiance of the surface under the cursor: a one-pixel render of each. */
  pick() {
    this.pickStale = false;
    if (!this.cursor) return;
    const dpr = this.renderer.getPixelRatio();
    const x = Math.floor(this.cursor.x * dpr);
    const y = Math.floor(this.cursor.y * dpr);
    this.pickTarget.setSize(1, 1);
    this.camera.setViewOffset(this.width, this.height, x, y, 1, 1);
    const read = (output) => {
      this.setOutput(output);
      this.renderer.setRenderTarget(this.pickTarget);
      this.renderer.clear();
      this.renderer.render(this.scene, this.camera);
      this.renderer.setRenderTarget(null);
      const v = new Float32Array(4);
      this.renderer.readRenderTargetPixels(this.pickTarget, 0, 0, 1, 1, v);
      return v;
    };
    const radiance = read(OUTPUT_RADIANCE);
    const irradiance = read(OUTPUT_IRRADIANCE);
    this.setOutput(OUTPUT_RADIANCE);
    this.camera.clearViewOffset();
    // A pixel that shows no surface reads 0 radiance and 0 irradiance, as a photometer pointed at the void would.
    this.lastPick = { radiance: Array.from(radiance.subarray(0, 3)), irradiance: Array.from(irradiance.subarray(0, 3)) };
    this.overlay.readout(
      LUMINOUS_EFFICACY * relativeLuminance(radiance[0], radiance[1], radiance[2]),
      LUMINOUS_EFFICACY * relativeLuminance(irradiance[0], irradiance[1], irradiance[2]),
    );
  }

  frame(time) {
    const seconds = (time - this.lastTime) / 1000;
    this.lastTime = time;
    if (this.controls.update(seconds)) this.viewChanged();

    const op = this.operator;
    const parameters = toneParameters(op, this.settings.parameters);
    const adaptive = op.adaptive(parameters);
    if (this.needsDraw) {
      this.renderRadiance(this.radiance);
      // Adaptive operators follow the view, throttled while it moves; the others need no statistics.
      if (this.statisticsStale && (adaptive || !this.controls.moving) && time - this.statisticsTime >= STATISTICS_INTERVAL_MS)
        this.readStatistics();
      if (this.statistics === null) this.readStatistics();
      const mapped = op.create(this.statistics, parameters);
      setToneUniforms(this.display.uniforms, mapped);
      this.overlay.describe(mapped.describe);
      this.display.draw(this.renderer, this.radiance, this.samplesPerPixel, null);
      ++this.frameCount;
      // Done when the picture shows the statistics of its own view; otherwise draw again when they may be read.
      this.needsDraw = this.statisticsStale && adaptive;
      if (!this.needsDraw && !this.ready) {
        this.ready = true;
        document.title = 'ready';
      }
      this.frameTimes.push(time);
      while (this.frameTimes.length > 0 && time - this.frameTimes[0] > 1000) this.frameTimes.shift();
      if (this.frameTimes.length > 1) this.overlay.frameRate((this.frameTimes.length - 1) / ((time - this.frameTimes[0]) / 1000));
    }
    if (this.pickStale && !this.controls.moving) this.pick();
  }
}

async function main() {
  let settings;
  try {
    settings = readSettings();
    const model = query.get('model');
    if (!model) throw new Error('no model: add ?model=FILE.glb to the address (a path relative to this page), e.g. index.html?model=box.glb');
    const gltf = await loadModel(model);
    window.radiantViewer = new Viewer(gltf, settings);
  } catch (error) {
    console.error(error);
    showError(error.message ?? String(error));
  }
}

main();
