// web_fps.mjs - the browser page's frame rate in headless Chromium, scene by scene, over several rounds.
// Usage: node web_fps.mjs BUILD_WEB_DIR SECONDS ROUNDS QUERY... (each QUERY an address's "?size=...&show=...").
// Prints one line per round and scene (frames per second, and facet's draw plus the canvas copy in ms), then the
// medians. Scenes alternate within each round: the host is noisy.
import { launch, measureRate, openPage, serve } from '../tests/e2e/lib/web_harness.mjs';

const [buildDir, seconds, rounds, ...queries] = process.argv.slice(2);
const { server, url } = await serve(buildDir);
const browser = await launch(buildDir);
const results = new Map(queries.map((q) => [q, []]));
try {
  for (let round = 1; round <= Number(rounds); ++round) {
    for (const query of queries) {
      const { page, errors } = await openPage(browser, url, query);
      await page.waitForTimeout(1000);  // the model loaded and the first frames drawn
      const { fps, ms } = await measureRate(page, Number(seconds));
      const error = await page.evaluate(() => document.getElementById('error').textContent);
      if (errors.length || error) throw new Error(`${query}: ${[...errors, error].join(' | ')}`);
      console.log(`round ${round} ${query} fps=${fps.toFixed(1)} frame_ms=${ms.toFixed(2)}`);
      results.get(query).push({ fps, ms });
      await page.close();
    }
  }
} finally {
  await browser.close();
  server.close();
}
const median = (values) => {
  const v = [...values].sort((a, b) => a - b);
  return v.length % 2 ? v[(v.length - 1) / 2] : (v[v.length / 2 - 1] + v[v.length / 2]) / 2;
};
for (const [query, runs] of results)
  console.log(`median ${query} fps=${median(runs.map((r) => r.fps)).toFixed(1)} ` +
              `frame_ms=${median(runs.map((r) => r.ms)).toFixed(2)}`);
