// Screenshots of a rendered report for the README (docs/): the first screen at 1400x900 and the
// first image strip. Usage: node report/screenshots.mjs REPORT_DIR OUT_DIR
// Uses Debian's chromium through playwright-core, like the browser test (CHROMIUM overrides).
import {chromium} from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {pathToFileURL} from 'node:url';

const [reportDir, outDir] = process.argv.slice(2);
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-chromium-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking'],
  viewport: {width: 1400, height: 900},
});
const page = await browser.newPage();
await page.goto(pathToFileURL(path.join(reportDir, 'report.html')).href, {waitUntil: 'load'});
await page.waitForTimeout(1500);  // vega views draw after load
await page.screenshot({path: path.join(outDir, 'report-first-screen.png')});
const strip = page.locator('.strip').first();
await strip.scrollIntoViewIfNeeded();
await strip.screenshot({path: path.join(outDir, 'report-image-strip.png')});
await browser.close();
fs.rmSync(profile, {recursive: true, force: true});
console.log(`screenshots in ${outDir}`);
