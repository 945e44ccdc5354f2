// page.js - the page's side: canvas, menus, keys, mouse and dropped files driving facet's WebAssembly module.
'use strict';

const canvas = document.getElementById('view');
const context = canvas.getContext('2d');
const stage = document.getElementById('stage');
const sceneMenu = document.getElementById('scene');
const shadingMenu = document.getElementById('shading');
const fileInput = document.getElementById('file');
const fpsText = document.getElementById('fps');
const statusText = document.getElementById('status');
const errorText = document.getElementById('error');
const params = new URLSearchParams(location.search);

const kModelExtensions = ['.obj', '.gltf', '.glb', '.ply', '.stl', '.xyz', '.pts', '.pcd', '.splat'];
const kToggleBits = { w: 1, e: 2, c: 4, z: 8, p: 16, s: 32, o: 64, a: 128, ' ': 256, m: 1024 };

// facet.js (loaded after this file) fills in this object and calls onRuntimeInitialized when the module is ready.
// facet's warnings (a model's dropped faces, say) go to the console as warnings, not errors.
var Module = {
  print: (text) => console.log(text),
  printErr: (text) => console.warn(text),
  onRuntimeInitialized: start,
};

// Calls a module function taking one string, which is copied into the module's memory for the call.
function withString(text, call) {
  const bytes = new TextEncoder().encode(text + '\0');
  const pointer = Module._malloc(bytes.length);
  try {
    Module.HEAPU8.set(bytes, pointer);
    return call(pointer);
  } finally {
    Module._free(pointer);
  }
}

function showError(message) {
  errorText.textContent = message;
  errorText.hidden = message === '';
}

function updateControls() {
  const bits = Module._facet_page_toggles();
  for (const button of document.querySelectorAll('button[data-key]')) {
    const bit = kToggleBits[button.dataset.key];
    if (bit) button.setAttribute('aria-pressed', String((bits & bit) !== 0));
  }
  shadingMenu.value = String(bits >> 12);
  document.querySelector('.help').hidden = (bits & 512) !== 0;
  statusText.textContent = Module.UTF8ToString(Module._facet_page_status());
}

function pressKey(key) {
  if (!Module._facet_page_key(key.charCodeAt(0))) return false;
  updateControls();
  return true;
}

function showDemo(name) {
  const error = Module.UTF8ToString(withString(name, Module._facet_page_show_demo));
  showError(error);
  updateControls();
}

// Model files live in the module's file system, one folder per opening, so an OBJ finds its MTL and textures and
// a glTF its buffers. The folder of the model shown stays (textures are decoded when first drawn).
let openings = 0;
let shownFolder = null;

function removeFolder(folder) {
  for (const name of Module.FS.readdir(folder)) {
    if (name !== '.' && name !== '..') Module.FS.unlink(`${folder}/${name}`);
  }
  Module.FS.rmdir(folder);
}

// Opens the first model among named byte arrays ([{name, bytes}]); on failure the previous model stays on screen
// and the error, naming the file, is shown.
function openModel(files, label) {
  const model = files.find((f) => kModelExtensions.some((ext) => f.name.toLowerCase().endsWith(ext)));
  if (!model) {
    showError(`${files.map((f) => f.name).join(', ')}: no model file among them (OBJ, glTF/GLB, PLY or STL)`);
    return false;
  }
  const folder = `/input/${++openings}`;
  Module.FS.mkdirTree(folder);
  for (const f of files) Module.FS.writeFile(`${folder}/${f.name.replace(/[\/\\]/g, '_')}`, f.bytes);
  const path = `${folder}/${model.name.replace(/[\/\\]/g, '_')}`;
  const error = Module.UTF8ToString(withString(path, Module._facet_page_open_model));
  if (error) {
    removeFolder(folder);
    showError(error.split(`${folder}/`).join(''));
    updateControls();
    return false;
  }
  if (shownFolder) removeFolder(shownFolder);
  shownFolder = folder;
  showError('');
  const option = sceneMenu.querySelector('option[value="file"]');
  option.textContent = label || model.name;
  if (!label) {
    option.hidden = false;
    sceneMenu.value = 'file';
  }
  updateControls();
  return true;
}

// Lights the model's own look by an equirectangular .hdr (the page's --hdri); the file stays in the module's file
// system while it is in use, as facet reads it again for another up axis.
let environmentFile = null;

function openEnvironment(file) {
  const path = `/input/environment-${++openings}.hdr`;
  Module.FS.mkdirTree('/input');
  Module.FS.writeFile(path, file.bytes);
  const error = Module.UTF8ToString(withString(path, Module._facet_page_open_environment));
  if (error) {
    Module.FS.unlink(path);
    showError(error.split(path).join(file.name));
    return false;
  }
  if (environmentFile) Module.FS.unlink(environmentFile);
  environmentFile = path;
  showError('');
  return true;
}

async function openFiles(fileList) {
  const files = await Promise.all(
    Array.from(fileList, async (f) => ({ name: f.name, bytes: new Uint8Array(await f.arrayBuffer()) })));
  const isEnvironment = (f) => f.name.toLowerCase().endsWith('.hdr');
  const environment = files.find(isEnvironment);
  if (environment && !openEnvironment(environment)) return;
  const models = files.filter((f) => !isEnvironment(f));
  if (models.length) openModel(models);
}

async function openUrl(url) {
  const response = await fetch(url);
  if (!response.ok) {
    showError(`${url}: ${response.status} ${response.statusText}`);
    return;
  }
  const name = url.split('/').pop();
  openModel([{ name, bytes: new Uint8Array(await response.arrayBuffer()) }], name);
}

function choose(value) {
  if (value.startsWith('demo:')) showDemo(value.slice(5));
  else if (value.startsWith('model:')) openUrl(value.slice(6));
}

// The canvas is drawn at its CSS size in CSS pixels (not device pixels: a quarter of the work on a 2x screen),
// unless the address fixes it: ?size=800x600.
const fixedSize = /^(\d+)x(\d+)$/.exec(params.get('size') || '');
function fitCanvas() {
  if (fixedSize) return;
  canvas.width = Math.max(1, Math.floor(stage.clientWidth));
  canvas.height = Math.max(1, Math.floor(stage.clientHeight));
}

// Frames per second and the time facet takes to draw one, over the last half second; and running totals, which
// the frame-rate benchmark reads.
let frames = 0, drawMs = 0, since = performance.now();
window.facetTotals = { frames: 0, drawMs: 0 };

function frame(now) {
  const width = canvas.width, height = canvas.height;
  const start = performance.now();
  const pixels = Module._facet_page_frame(width, height, now / 1000);
  if (pixels) {
    const rgba = new Uint8ClampedArray(Module.HEAPU8.buffer, pixels, width * height * 4);
    context.putImageData(new ImageData(rgba, width, height), 0, 0);
  } else {
    showError(Module.UTF8ToString(Module._facet_page_error()));
  }
  const took = performance.now() - start;
  drawMs += took;
  ++frames;
  window.facetTotals.frames += 1;
  window.facetTotals.drawMs += took;
  if (now - since >= 500) {
    const fps = (frames * 1000) / (now - since);
    fpsText.textContent = `${fps.toFixed(1)} fps, ${(drawMs / frames).toFixed(1)} ms a frame, ${width}x${height}`;
    fpsText.dataset.fps = fps.toFixed(1);
    frames = 0;
    drawMs = 0;
    since = now;
  }
  requestAnimationFrame(frame);
}

function start() {
  if (fixedSize) {
    canvas.width = Number(fixedSize[1]);
    canvas.height = Number(fixedSize[2]);
    canvas.classList.add('fixed');
  } else {
    new ResizeObserver(fitCanvas).observe(stage);
    fitCanvas();
  }

  document.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey || e.key.length !== 1) return;
    if (e.target instanceof HTMLSelectElement || e.target instanceof HTMLInputElement) return;
    if (pressKey(e.key.toLowerCase())) e.preventDefault();
  });
  for (const button of document.querySelectorAll('button[data-key]'))
    button.addEventListener('click', () => pressKey(button.dataset.key));
  shadingMenu.addEventListener('change', () => pressKey(shadingMenu.value));
  sceneMenu.addEventListener('change', () => choose(sceneMenu.value));
  document.getElementById('open').addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    openFiles(fileInput.files);
    fileInput.value = '';
  });

  let last = null;
  canvas.addEventListener('pointerdown', (e) => {
    canvas.setPointerCapture(e.pointerId);
    canvas.focus();
    last = [e.clientX, e.clientY];
  });
  canvas.addEventListener('pointermove', (e) => {
    if (!last || !e.buttons) return;
    const scale = canvas.width / canvas.clientWidth;
    const dx = (e.clientX - last[0]) * scale, dy = (e.clientY - last[1]) * scale;
    last = [e.clientX, e.clientY];
    const pan = (e.buttons & 2) !== 0 || ((e.buttons & 1) !== 0 && e.shiftKey);
    Module._facet_page_drag(dx, dy, pan ? 1 : 0, canvas.height);
  });
  canvas.addEventListener('pointerup', () => (last = null));
  canvas.addEventListener('contextmenu', (e) => e.preventDefault());
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    Module._facet_page_zoom(-e.deltaY / (e.deltaMode === 0 ? 100 : 3));
  }, { passive: false });

  stage.addEventListener('dragenter', (e) => {
    e.preventDefault();
    stage.classList.add('dragging');
  });
  stage.addEventListener('dragover', (e) => e.preventDefault());
  stage.addEventListener('dragleave', (e) => {
    if (e.target === stage || e.target === canvas) stage.classList.remove('dragging');
  });
  stage.addEventListener('drop', (e) => {
    e.preventDefault();
    stage.classList.remove('dragging');
    openFiles(e.dataTransfer.files);
  });

  const show = params.get('show');
  if (show) {
    const option = Array.from(sceneMenu.options).find((o) => o.value === show);
    if (option) sceneMenu.value = show;
    choose(show);
  }
  updateControls();
  requestAnimationFrame(frame);
}
