// three_render.mjs - renders glTF models in three.js (headless Chromium) through a facet camera JSON, lit only by an
// equirectangular .hdr environment, as the reference for facet's PBR shading (see run.sh).
// Usage: node three_render.mjs --model M.glb --camera cam.json --hdri env.hdr --output out.png
//          [--background R,G,B] [--tone-mapping neutral|aces|none] [--exposure 1]
//        node three_render.mjs --jobs jobs.json [same options as defaults for every job]
// jobs.json is a list of {"model", "camera", "hdri", "output"[, "background": [r, g, b], "toneMapping", "exposure"]}.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { launch, serve } from '../../tests/e2e/lib/web_harness.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));

// WebGL2 from SwiftShader (through ANGLE and Vulkan), named so a machine with a GPU draws the same as one without;
// recent Chromium only falls back to SwiftShader for WebGL when told it may (--enable-unsafe-swiftshader).
const kChromiumFlags = '--use-angle=swiftshader --enable-unsafe-swiftshader';

function parseArgs(argv) {
  const options = { background: [0.42, 0.45, 0.5], toneMapping: 'neutral', exposure: 1 };
  for (let i = 0; i < argv.length; i += 2) {
    const [flag, value] = [argv[i], argv[i + 1]];
    if (value === undefined) throw new Error(`${flag} needs a value`);
    if (flag === '--model') options.model = value;
    else if (flag === '--camera') options.camera = value;
    else if (flag === '--hdri') options.hdri = value;
    else if (flag === '--output') options.output = value;
    else if (flag === '--jobs') options.jobs = value;
    else if (flag === '--background') options.background = value.split(',').map(Number);
    else if (flag === '--tone-mapping') options.toneMapping = value;
    else if (flag === '--exposure') options.exposure = Number(value);
    else throw new Error(`unknown option ${flag}`);
  }
  return options;
}

// The page: three.js and its addons by importmap from the installed package, exposed to renderJob() below.
const kPage = `<!doctype html>
<html><body style="margin:0">
<script type="importmap">
{ "imports": { "three": "./three/build/three.module.js", "three/addons/": "./three/examples/jsm/" } }
</script>
<script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { HDRLoader } from 'three/addons/loaders/HDRLoader.js';
window.lib = { THREE, GLTFLoader, HDRLoader };
</script>
</body></html>`;

// Runs inside the page (serialised by playwright): one render, returned as a PNG data URL.
async function renderJob(job) {
  const { THREE, GLTFLoader, HDRLoader } = window.lib;
  const cam = job.camera;
  // One renderer for every job: shaders compile once, and each environment is prefiltered once (about 3 s of
  // SwiftShader's time, which lands on the first readback since WebGL runs lazily).
  if (!window.renderer) {
    // preserveDrawingBuffer so toDataURL still sees the frame; alpha false gives an opaque RGB frame like facet's.
    window.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true, alpha: false });
    window.environments = new Map();
    document.body.appendChild(window.renderer.domElement);
  }
  const renderer = window.renderer;
  renderer.setPixelRatio(1);
  renderer.setSize(cam.width, cam.height, false);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  // 'none' is LinearToneMapping: the same as NoToneMapping at exposure 1, but it still applies the exposure.
  renderer.toneMapping = { neutral: THREE.NeutralToneMapping, aces: THREE.ACESFilmicToneMapping,
                           none: THREE.LinearToneMapping }[job.toneMapping];
  renderer.toneMappingExposure = job.exposure;

  // Each .hdr prefiltered once (fromEquirectangular: a cube of max(256, width / 4) texels a side, half float).
  if (!window.environments.has(job.hdri)) {
    const hdr = await new HDRLoader().loadAsync(job.hdri);
    hdr.mapping = THREE.EquirectangularReflectionMapping;
    const pmrem = new THREE.PMREMGenerator(renderer);
    window.environments.set(job.hdri, pmrem.fromEquirectangular(hdr));
    pmrem.dispose();
    hdr.dispose();
  }
  const envTarget = window.environments.get(job.hdri);
  const scene = new THREE.Scene();
  scene.environment = envTarget.texture;
  scene.environmentIntensity = 1;
  // The flag's values are display (sRGB) values; three.js clears with them as given, untouched by tone mapping.
  scene.background = new THREE.Color().setRGB(...job.background, THREE.SRGBColorSpace);
  const gltf = await new GLTFLoader().loadAsync(job.model);
  scene.add(gltf.scene);  // as loaded: facet's camera is in the model's own world coordinates

  // The camera's matrices exactly as facet used them; a parallel view needs an OrthographicCamera so the shaders
  // take the view direction as constant (isOrthographic).
  const camera = cam.projection === 'parallel' ? new THREE.OrthographicCamera() : new THREE.PerspectiveCamera();
  camera.near = cam.near;
  camera.far = cam.far;
  camera.matrixAutoUpdate = false;
  camera.matrix.set(...cam.world_from_camera.flat());  // Matrix4.set takes row-major arguments
  camera.matrixWorldNeedsUpdate = true;
  camera.updateMatrixWorld(true);
  // Set last and never followed by updateProjectionMatrix(), which would rebuild it from fov/near/far.
  camera.projectionMatrix.set(...cam.clip_from_view.flat());
  camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();

  const start = performance.now();
  renderer.render(scene, camera);
  const url = renderer.domElement.toDataURL('image/png');
  const ms = performance.now() - start;
  const info = { triangles: renderer.info.render.triangles, pmremSize: envTarget.width };

  // The model's GPU buffers and textures go; the compiled programs stay for the next job.
  scene.traverse((object) => {
    if (object.geometry) object.geometry.dispose();
    for (const material of [object.material || []].flat()) {
      for (const value of Object.values(material)) if (value && value.isTexture) value.dispose();
      material.dispose();
    }
  });
  return { url, ms, info };
}

async function main() {
  const options = parseArgs(process.argv.slice(2));
  const jobs = options.jobs ? JSON.parse(fs.readFileSync(options.jobs, 'utf8')) : [{}];
  const defaults = { ...options };
  delete defaults.jobs;
  const list = jobs.map((job) => ({ ...defaults, ...job }));
  for (const job of list) {
    for (const key of ['model', 'camera', 'hdri', 'output']) {
      if (!job[key]) throw new Error(`missing --${key}`);
    }
    if (!['neutral', 'aces', 'none'].includes(job.toneMapping)) throw new Error(`bad tone mapping ${job.toneMapping}`);
  }

  // The server only sees one folder: links in a scratch folder to three.js and to each model's folder (a .gltf
  // names its .bin and images relative to itself) and each .hdr.
  const root = fs.mkdtempSync(path.join(os.tmpdir(), 'facet-three-'));
  fs.writeFileSync(path.join(root, 'index.html'), kPage);
  fs.symlinkSync(path.join(here, 'node_modules', 'three'), path.join(root, 'three'));
  const hdris = new Map();  // one name per .hdr, so the page prefilters each once
  const pageJobs = list.map((job, i) => {
    fs.symlinkSync(path.resolve(path.dirname(job.model)), path.join(root, `m${i}`));
    const hdri = path.resolve(job.hdri);
    if (!hdris.has(hdri)) {
      hdris.set(hdri, `e${hdris.size}.hdr`);
      fs.symlinkSync(hdri, path.join(root, hdris.get(hdri)));
    }
    return {
      model: `m${i}/${encodeURIComponent(path.basename(job.model))}`, hdri: hdris.get(hdri),
      camera: JSON.parse(fs.readFileSync(job.camera, 'utf8')),
      background: job.background, toneMapping: job.toneMapping, exposure: job.exposure,
    };
  });

  process.env.CHROMIUM_FLAGS = `${kChromiumFlags} ${process.env.CHROMIUM_FLAGS || ''}`;
  const { server, url } = await serve(root);
  const browser = await launch(here);
  let failed = 0;
  try {
    const page = await browser.newPage();
    let errors = [];
    page.on('console', (message) => {
      if (message.type() === 'error') errors.push(`console: ${message.text()}`);
      else if (message.type() === 'warning') console.error(`  page warning: ${message.text()}`);
    });
    page.on('pageerror', (error) => errors.push(`exception: ${error.message}`));
    page.on('requestfailed', (request) => errors.push(`request failed: ${request.url()}`));
    page.on('response', (response) => {
      if (response.status() >= 400) errors.push(`HTTP ${response.status()}: ${response.url()}`);
    });
    await page.goto(url);
    await page.waitForFunction(() => window.lib !== undefined, null, { timeout: 60000 });
    for (const [i, job] of pageJobs.entries()) {
      errors = [];
      const started = Date.now();
      let result = null;
      try {
        result = await page.evaluate(renderJob, job);
      } catch (error) {
        errors.push(`exception: ${error.message.split('\n')[0]}`);
      }
      const name = path.basename(list[i].model);
      if (errors.length) {  // no image then, so a half-loaded model is never compared
        failed += 1;
        console.error(`three.js FAILED ${name}:\n  ${errors.join('\n  ')}`);
      } else {
        fs.writeFileSync(list[i].output, Buffer.from(result.url.split(',')[1], 'base64'));
        console.log(`three.js ${name} -> ${list[i].output} (${Date.now() - started} ms in all, draw+readback ` +
                    `${result.ms.toFixed(0)} ms, ${result.info.triangles} triangles, PMREM ${result.info.pmremSize})`);
      }
    }
  } finally {
    await browser.close();
    server.close();
    fs.rmSync(root, { recursive: true, force: true });
  }
  process.exit(failed ? 1 : 0);
}

main().catch((error) => {
  console.error(`three_render.mjs: ${error.message}`);
  process.exit(1);
});
