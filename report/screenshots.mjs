// Screenshots of a rendered report for the README (docs/), at 1400 px wide: the first screen, the
// speed-vs-accuracy chart, the triangle-size chart, the side-by-side view (its first screen: the
// flip viewer and the first rows) and the first image strip.
// Usage: node report/screenshots.mjs REPORT_DIR OUT_DIR
// Uses Debian's chromium through playwright-core, like the browser test (CHROMIUM overrides).
import {chromium} from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {pathToFileURL} from 'node:url';

const [reportDir, outDir] = process.argv.slice(2);
if (!reportDir || !outDir) {
  console.error('usage: node report/screenshots.mjs REPORT_DIR OUT_DIR');
  process.exit(2);
}
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-chromium-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking'],
  viewport: {width: 1400, height: 900},
});
const page = await browser.newPage();
await page.goto(pathToFileURL(path.join(reportDir, 'report.html')).href, {waitUntil: 'load'});
await page.waitForFunction(() => document.body.dataset.charts, null, {timeout: 60000});
const shots = [];
const save = (name) => (shots.push(name), path.join(outDir, name));
// Waits until the images in the viewport have loaded (they load lazily as they scroll in).
const settle = () => page.evaluate(() => Promise.all([...document.images]
  .filter((i) => { const r = i.getBoundingClientRect(); return r.bottom > 0 && r.top < innerHeight; })
  .map((i) => (i.complete ? null : new Promise((ok) => { i.onload = i.onerror = ok; })))));
await page.screenshot({path: save('report-first-screen.png')});
for (const [id, name] of [['speed_gpu_ms', 'report-speed-vs-accuracy.png'], ['triangle_sizes', 'report-triangle-sizes.png']]) {
  const chart = page.locator(`figure:has(#chart-${id})`);
  if (await chart.count()) await chart.screenshot({path: save(name)});
  else console.log(`no chart ${id} in this report`);
}
const side = page.locator('#side-by-side');
if (await side.count()) {
  await side.evaluate((h) => h.scrollIntoView());
  await settle();
  await page.screenshot({path: save('report-side-by-side.png')});
} else {
  console.log('no side-by-side view in this report (no frame has images of two schemes)');
}
const strip = page.locator('.strip').first();
if (await strip.count()) {
  await strip.scrollIntoViewIfNeeded();
  await settle();
  await strip.screenshot({path: save('report-image-strip.png')});
}
await browser.close();
fs.rmSync(profile, {recursive: true, force: true});
console.log(`screenshots in ${outDir}: ${shots.join(', ')}`);
