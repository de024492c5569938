// Times how long headless Chromium takes to open a report: navigation start to the page's 'load'
// event (every linked resource that is not lazy fetched), best of N tries, on this machine.
// Usage: node report/open-time.mjs REPORT_HTML [TRIES=3]
import {chromium} from 'playwright-core';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {pathToFileURL} from 'node:url';

const [file, triesArg] = process.argv.slice(2);
if (!file) {
  console.error('usage: node report/open-time.mjs REPORT_HTML [TRIES=3]');
  process.exit(2);
}
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-chromium-'));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true,
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking'],
  viewport: {width: 1400, height: 900},
});
const times = [];
for (let i = 0; i < Number(triesArg || 3); ++i) {
  const page = await browser.newPage();
  const start = Date.now();
  await page.goto(pathToFileURL(path.resolve(file)).href, {waitUntil: 'load', timeout: 120000});
  times.push(Date.now() - start);
  await page.close();
}
await browser.close();
fs.rmSync(profile, {recursive: true, force: true});
const mb = (fs.statSync(file).size / 1e6).toFixed(1);
console.log(`${file}: ${mb} MB, opened ('load') in ${times.map((t) => (t / 1000).toFixed(2)).join(', ')} s; ` +
            `best ${(Math.min(...times) / 1000).toFixed(2)} s`);
