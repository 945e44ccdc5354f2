// web_harness.mjs - serves the built page on 127.0.0.1 and opens it in Debian's headless Chromium (playwright-core).
// Shared by the page's end-to-end test and its frame-rate benchmark.
import fs from 'node:fs';
import http from 'node:http';
import { createRequire } from 'node:module';
import path from 'node:path';

const kTypes = {
  '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css',
  '.wasm': 'application/wasm', '.json': 'application/json', '.png': 'image/png',
};

// A plain static file server, as any would be (no special headers): files under root, on a free port.
export async function serve(root) {
  root = path.resolve(root);
  const server = http.createServer((request, response) => {
    const name = decodeURIComponent(new URL(request.url, 'http://127.0.0.1').pathname);
    let file = path.join(root, name.endsWith('/') ? name + 'index.html' : name);
    if (!file.startsWith(root + path.sep)) file = '';
    fs.readFile(file, (error, data) => {
      if (error) {
        response.writeHead(404).end('not found');
        return;
      }
      response.writeHead(200, { 'Content-Type': kTypes[path.extname(file)] || 'application/octet-stream' });
      response.end(data);
    });
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { server, url: `http://127.0.0.1:${server.address().port}/` };
}

// Debian's chromium, headless, through the playwright-core that `npm ci` put next to the page.
export async function launch(buildDir) {
  const { chromium } = createRequire(path.join(path.resolve(buildDir), 'package.json'))('playwright-core');
  const root = typeof process.getuid === 'function' && process.getuid() === 0;
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    // Chromium's sandbox refuses to start as root; CHROMIUM_FLAGS adds flags for experiments.
    args: [...(root ? ['--no-sandbox'] : []), ...(process.env.CHROMIUM_FLAGS || '').split(' ').filter(Boolean)],
  });
}

// Opens the page at `query` (e.g. "?size=800x600") and waits until it has drawn and reported a rate. Console errors
// and uncaught exceptions are collected in the returned `errors`.
export async function openPage(browser, url, query = '') {
  const page = await browser.newPage();
  const errors = [];
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(`console: ${message.text()}`);
  });
  page.on('pageerror', (error) => errors.push(`exception: ${error.message}`));
  await page.goto(url + query);
  await page.waitForFunction(() => document.getElementById('fps').dataset.fps !== undefined, null,
                             { timeout: 60000 });
  return { page, errors };
}

// The page's frame rate and mean time to draw a frame (facet plus the canvas copy) over the next `seconds`.
export async function measureRate(page, seconds) {
  const totals = () => page.evaluate(() => ({ ...window.facetTotals, now: performance.now() }));
  const before = await totals();
  await page.waitForTimeout(seconds * 1000);
  const after = await totals();
  const frames = after.frames - before.frames;
  return { fps: (1000 * frames) / (after.now - before.now), ms: (after.drawMs - before.drawMs) / Math.max(frames, 1) };
}
