// web_page.mjs - drives the built page in headless Chromium: it draws, animates, pauses, takes keys and dropped files.
// Usage: node web_page.mjs BUILD_WEB_DIR OUT_DIR. One line per check; exits 1 if any fails. Leaves the canvas
// showing the sample model in OUT_DIR/page_wuson.png.
import fs from 'node:fs';
import path from 'node:path';

import { launch, openPage, serve } from './lib/web_harness.mjs';

const [buildDir, outDir] = process.argv.slice(2);
fs.mkdirSync(outDir, { recursive: true });
let passed = 0, failed = 0;
function check(ok, name, detail = '') {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${!ok && detail ? ': ' + detail : ''}`);
  if (ok) ++passed;
  else ++failed;
}

// The canvas's pixels: a hash, how many distinct colours (up to 64) it holds, and the share of pixels that differ
// from the top left one (the background).
const snapshot = (page) => page.evaluate(() => {
  const canvas = document.getElementById('view');
  const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
  let hash = 2166136261;
  const colours = new Set();
  const background = (data[0] | data[1] << 8 | data[2] << 16 | data[3] << 24) >>> 0;
  let drawn = 0;
  for (let i = 0; i < data.length; i += 4) {
    const rgba = (data[i] | data[i + 1] << 8 | data[i + 2] << 16 | data[i + 3] << 24) >>> 0;
    hash = Math.imul(hash ^ rgba, 16777619) >>> 0;
    if (colours.size < 64) colours.add(rgba);
    drawn += rgba !== background;
  }
  return { hash, colours: colours.size, drawn: drawn / (data.length / 4) };
});
const text = (page, id) => page.evaluate((id) => document.getElementById(id).textContent, id);
const visible = (page, id) => page.evaluate((id) => !document.getElementById(id).hidden, id);
// Two animation frames: whatever a key or a drop asked for is on the canvas.
const settle = (page) => page.evaluate(() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))));

// Files dropped on the canvas together, as a user's drag from their disk delivers them: [[name, bytes], ...].
async function dropFiles(page, files) {
  await page.evaluate((files) => {
    const transfer = new DataTransfer();
    for (const [name, data] of files) transfer.items.add(new File([new Uint8Array(data)], name));
    document.getElementById('view').dispatchEvent(
      new DragEvent('drop', { dataTransfer: transfer, bubbles: true, cancelable: true }));
  }, files.map(([name, bytes]) => [name, Array.from(bytes)]));
}
const drop = (page, name, bytes) => dropFiles(page, [[name, bytes]]);
const statusStarts = (page, name) =>
  page.waitForFunction((name) => document.getElementById('status').textContent.startsWith(name), name,
                       { timeout: 10000 }).catch(() => {});

const { server, url } = await serve(buildDir);
const browser = await launch(buildDir);
try {
  const { page, errors } = await openPage(browser, url, '?size=640x480');

  const first = await snapshot(page);
  check(first.colours >= 2 && first.drawn > 0.05, 'the canvas is not blank (the spinning cube)',
        `${first.colours} colours, ${(100 * first.drawn).toFixed(1)}% drawn`);
  // The animation moves with the clock; on a loaded machine a frame can take longer than a second to come.
  let moved = false;
  for (let waited = 0; waited < 10000 && !moved; waited += 250) {
    await page.waitForTimeout(250);
    moved = (await snapshot(page)).hash !== first.hash;
  }
  check(moved, 'the picture changes within seconds (the animation runs)');

  await page.keyboard.press('Space');
  await settle(page);
  const paused = await snapshot(page);
  await page.waitForTimeout(500);
  check((await snapshot(page)).hash === paused.hash, 'space pauses the animation');
  check((await text(page, 'status')).includes('paused'), 'the status line says paused');

  await page.keyboard.press('w');
  await settle(page);
  const wire = await snapshot(page);
  check(wire.hash !== paused.hash, 'w changes the paused picture (wireframe)');
  check((await page.getAttribute('button[data-key="w"]', 'aria-pressed')) === 'true', 'the wireframe button shows it');
  await page.keyboard.press('w');

  await page.selectOption('#scene', 'model:models/WusonOBJ.obj');
  await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('WusonOBJ.obj'));
  await settle(page);
  const sample = await snapshot(page);
  check(sample.colours >= 8 && sample.drawn > 0.05 && sample.hash !== paused.hash, 'the menu opens the sample model');
  // The page's picture of the sample model, for web_page.sh to compare with the CLI's.
  const png = await page.evaluate(() => document.getElementById('view').toDataURL('image/png'));
  fs.writeFileSync(path.join(outDir, 'page_wuson.png'), Buffer.from(png.split(',')[1], 'base64'));
  // m: the height colour map, and m again back to the model's own colours.
  await page.keyboard.press('m');
  await settle(page);
  const mapped = await snapshot(page);
  check(mapped.hash !== sample.hash && Math.abs(mapped.drawn - sample.drawn) < 0.01 &&
        (await page.getAttribute('button[data-key="m"]', 'aria-pressed')) === 'true' &&
        (await text(page, 'status')).includes('colour map height'), 'm colours the model by height, in its outline',
        `${(100 * sample.drawn).toFixed(1)}% -> ${(100 * mapped.drawn).toFixed(1)}% drawn`);
  await page.keyboard.press('m');
  await settle(page);
  check((await snapshot(page)).hash === sample.hash, 'm again shows the model\'s own colours');

  const spider = fs.readFileSync('/usr/share/assimp/models/STL/Spider_binary.stl');
  // Gaussian splats in the .splat format: a 20x20 grid of red to blue Gaussians, opacity 0.8.
  const splats = Buffer.alloc(400 * 32);
  for (let k = 0; k < 400; ++k) {
    const at = k * 32, x = (k % 20) / 10 - 0.95, y = Math.floor(k / 20) / 10 - 0.95;
    [x, y, 0, 0.06, 0.06, 0.06].forEach((v, i) => splats.writeFloatLE(v, at + 4 * i));
    [Math.round(255 * (k % 20) / 19), 64, Math.round(255 - 255 * (k % 20) / 19), 204, 255, 128, 128, 128]
      .forEach((v, i) => splats.writeUInt8(v, at + 24 + i));
  }
  await drop(page, 'grid.splat', splats);
  await statusStarts(page, 'grid.splat');
  await settle(page);
  const splatted = await snapshot(page);
  check(!(await visible(page, 'error')) && splatted.drawn > 0.2 && splatted.colours >= 16,
        'a dropped .splat file shows its Gaussians', `${(100 * splatted.drawn).toFixed(1)}% drawn, ` +
        `${splatted.colours} colours`);

  await drop(page, 'Spider_binary.stl', spider);
  await statusStarts(page, 'Spider_binary.stl');
  await settle(page);
  const dropped = await snapshot(page);
  check((await text(page, 'status')).startsWith('Spider_binary.stl') && dropped.hash !== sample.hash &&
        dropped.drawn > 0.02, 'a dropped model file replaces what was shown', await text(page, 'status'));
  check(!(await visible(page, 'error')), 'no error is shown after a good file');

  const box = await page.locator('#view').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 80, box.y + box.height / 2 + 20, { steps: 4 });
  await page.mouse.up();
  await settle(page);
  const turned = await snapshot(page);
  check(turned.hash !== dropped.hash && turned.drawn > 0.02, 'dragging orbits the model');
  await page.mouse.wheel(0, -300);
  await settle(page);
  const zoomed = await snapshot(page);
  check(zoomed.hash !== turned.hash && zoomed.drawn > turned.drawn, 'the wheel zooms in',
        `${(100 * turned.drawn).toFixed(1)}% -> ${(100 * zoomed.drawn).toFixed(1)}% drawn`);
  await page.keyboard.press('r');

  // A glTF with its buffer and texture image, dropped together: the texture is decoded in the tab.
  const folder = '/usr/share/assimp/models/glTF2/BoxTextured-glTF';
  await dropFiles(page, ['BoxTextured.gltf', 'BoxTextured0.bin', 'CesiumLogoFlat.png'].map(
    (name) => [name, fs.readFileSync(path.join(folder, name))]));
  await statusStarts(page, 'BoxTextured.gltf');
  await settle(page);
  const textured = await snapshot(page);
  check((await text(page, 'status')).startsWith('BoxTextured.gltf') && !(await visible(page, 'error')) &&
        textured.colours >= 32, 'a glTF dropped with its buffer and texture opens textured',
        `${await text(page, 'status')}; ${textured.colours} colours`);

  // A glTF's animation, paused (as the page still is), steps with the . key: 20 frames, 2/3 s, more than any of
  // simple_skin's held stretches (0.5 s).
  await drop(page, 'simple_skin.gltf', fs.readFileSync('/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf'));
  await statusStarts(page, 'simple_skin.gltf');
  await settle(page);
  const held = await snapshot(page);
  await page.waitForTimeout(300);
  const stillHeld = await snapshot(page);
  for (let k = 0; k < 20; ++k) await page.keyboard.press('.');
  await settle(page);
  const stepped = await snapshot(page);
  check(held.hash === stillHeld.hash && stepped.hash !== held.hash && stepped.drawn > 0.01,
        "a glTF's animation holds while paused and steps with .", `${(100 * stepped.drawn).toFixed(1)}% drawn`);

  await drop(page, 'Spider_binary.stl', spider);
  await statusStarts(page, 'Spider_binary.stl');
  await settle(page);
  const shown = await snapshot(page);

  await drop(page, 'broken.ply', Buffer.from('ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n1 2'));
  await page.waitForFunction(() => !document.getElementById('error').hidden, null, { timeout: 10000 }).catch(() => {});
  const error = await text(page, 'error');
  check((await visible(page, 'error')) && error.startsWith('broken.ply: ') && !error.includes('\n'),
        'a malformed file shows its one-line error', JSON.stringify(error));
  await settle(page);
  check((await text(page, 'status')).startsWith('Spider_binary.stl') && (await snapshot(page)).hash === shown.hash,
        'the previous model stays on screen');

  // An equirectangular .hdr dropped on the page lights the model's own look (the page's --hdri): a uniform red
  // environment turns the grey model red; a file that is no Radiance image is refused in one line, naming it.
  const header = Buffer.from('#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n');
  const red = Buffer.alloc(32 * 16 * 4);
  for (let i = 0; i < red.length; i += 4) red.set([128, 0, 0, 129], i);  // RGBE: radiance (1, 0, 0)
  const redness = () => page.evaluate(() => {  // red over green, summed over the canvas
    const canvas = document.getElementById('view');
    const data = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    let red = 0, green = 0;
    for (let i = 0; i < data.length; i += 4) red += data[i], green += data[i + 1];
    return red / green;
  });
  const before = await redness();
  await drop(page, 'red.hdr', Buffer.concat([header, red]));
  await settle(page);
  const lit = await snapshot(page);
  const reddish = (await redness()) > 1.1 * before;
  check(lit.hash !== shown.hash && reddish && !(await visible(page, 'error')) &&
        (await text(page, 'status')).startsWith('Spider_binary.stl'),
        'a dropped .hdr lights the model shown', await text(page, 'error'));
  await drop(page, 'fake.hdr', Buffer.from('not a radiance file'));
  await page.waitForFunction(() => !document.getElementById('error').hidden, null, { timeout: 10000 }).catch(() => {});
  const hdrError = await text(page, 'error');
  check((await visible(page, 'error')) && hdrError.startsWith('fake.hdr') && !hdrError.includes('\n'),
        'a bad .hdr shows its one-line error', JSON.stringify(hdrError));
  await settle(page);
  check((await snapshot(page)).hash === lit.hash, 'the previous environment stays');

  const fps = await page.evaluate(() => Number(document.getElementById('fps').dataset.fps));
  check(fps > 0 && /fps/.test(await text(page, 'fps')), '#fps reports the frame rate', `${fps}`);

  await page.screenshot({ path: path.join(outDir, 'page.png') });
  check(errors.length === 0, 'no console error or exception', errors.join(' | '));
} finally {
  await browser.close();
  server.close();
}
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
