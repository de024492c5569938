// Screenshots for reviewing a scenario sweep: the summary page's first screen and, for
// each RUN:CASE_ID:FRAME given, that run report's image strip of the case's frame.
// Usage: node report/review-shots.mjs SWEEP_DIR OUT_DIR [RUN:CASE_ID:FRAME ...]
import {chromium} from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {pathToFileURL} from 'node:url';

const [sweepDir, outDir, ...frames] = process.argv.slice(2);
fs.mkdirSync(outDir, {recursive: true});
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-chromium-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking'],
  viewport: {width: 1400, height: 900},
});
const page = await browser.newPage();
const errors = [];
page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
await page.goto(pathToFileURL(path.join(sweepDir, 'report', 'report.html')).href, {waitUntil: 'load'});
await page.screenshot({path: path.join(outDir, 'summary-first-screen.png')});
await page.locator('#scenarios').scrollIntoViewIfNeeded();
await page.screenshot({path: path.join(outDir, 'summary-observed.png')});
for (const spec of frames) {
  const [run, caseId, frame] = spec.split(':');
  await page.goto(pathToFileURL(path.join(sweepDir, run, 'report', 'report.html')).href, {waitUntil: 'load'});
  await page.waitForTimeout(500);
  const strip = page.locator(`[id="img-${caseId}-f${frame}"]`).first();
  if (await strip.count() === 0) { console.log(`${spec}: no strip with id img-${caseId}-f${frame}`); continue; }
  await strip.scrollIntoViewIfNeeded();
  await strip.screenshot({path: path.join(outDir, `${run}-${caseId}-f${frame}.png`)});
}
await browser.close();
fs.rmSync(profile, {recursive: true, force: true});
console.log(`screenshots in ${outDir}; console errors: ${errors.length}`);
