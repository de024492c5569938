// Browser test of report.html: `lodbench report`, then Debian's
// chromium (through playwright-core, never a downloaded browser) opens the page from file://
// offline and checks: no console errors or warnings, every chart drawn (vega views rendered =
// charts in the manifest), every image loaded (naturalWidth > 0), every worst frame the report
// names present with its images, every in-page link resolving, and the page no wider than the
// window. The check itself is tested: a planted missing image and the fixture's worst frames
// without images must be reported.
//   LODBENCH_BINARY   the lodbench executable (default build/lodbench)
//   CHROMIUM          the browser (default /usr/bin/chromium)
//   REPORT_TEST_OUT   where the reports and screenshots go (default: a fresh temp dir)
//   REPORT_TEST_RUN   a run directory to check instead of making the small lavapipe run
import {test, before, after} from 'node:test';
import assert from 'node:assert/strict';
import {execFileSync} from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';
import {chromium} from 'playwright-core';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const binary = process.env.LODBENCH_BINARY || path.join(root, 'build/lodbench');
const browserPath = process.env.CHROMIUM || '/usr/bin/chromium';
const out = process.env.REPORT_TEST_OUT || fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-report-'));
const fixture = path.join(root, 'tests/data/report_run');
const kWidth = 1400;

// Offline and quiet: no GPU, no network services, no first-run UI, a profile of its own.
const launchArgs = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
                    '--disable-background-networking', '--disable-component-update', '--disable-sync'];

let browser, profile;
before(async () => {
  fs.rmSync(out, {recursive: true, force: true});
  fs.mkdirSync(out, {recursive: true});
  profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-chromium-'));
  // playwright-core passes the fresh profile as --user-data-dir.
  browser = await chromium.launchPersistentContext(profile, {executablePath: browserPath, headless: true,
                                                             args: launchArgs, viewport: {width: kWidth, height: 900}});
});
after(async () => {
  await browser?.close();
  fs.rmSync(profile, {recursive: true, force: true});
});

const lodbench = (...args) => execFileSync(binary, args, {stdio: 'inherit', env: {...process.env, LODBENCH_VALIDATION: '1'}});
const copyRun = (src, name) => {
  const dst = path.join(out, name);
  fs.cpSync(src, dst, {recursive: true, filter: (s) => path.basename(s) !== 'report'});
  return dst;
};

// Opens <reportDir>/report.html and returns everything that is wrong with it, one line each.
async function inspect(reportDir, screenshot) {
  const manifest = JSON.parse(fs.readFileSync(path.join(reportDir, 'manifest.json'), 'utf8'));
  const page = await browser.newPage();
  const problems = [];
  // Vega reports spec problems as console warnings: treat them like errors.
  page.on('console', (m) => { if (['error', 'warning'].includes(m.type())) problems.push(`console ${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push('page error: ' + e.message));
  // Any request that is not the page itself or inline data would mean the page is not self-contained.
  page.on('request', (r) => { if (!/^(file|data|about|blob):/.test(r.url())) problems.push('external request: ' + r.url()); });
  try {
    await page.goto(pathToFileURL(path.join(reportDir, 'report.html')).href);
    await page.waitForFunction(() => document.body.dataset.charts, null, {timeout: 30000});
    const state = await page.evaluate(() => document.body.dataset.charts);
    if (state !== 'done') problems.push(`charts: ${state}`);
    const found = await page.evaluate((expected) => {
      const p = [];
      // Charts: one container per manifest chart, each with one drawn Vega view holding data marks.
      const boxes = [...document.querySelectorAll('.chart')];
      const drawn = boxes.filter((el) => el.querySelectorAll('svg.marks').length === 1 &&
        el.querySelectorAll('svg.marks g.role-mark > path, svg.marks g.role-mark > rect, svg.marks g.role-mark > text').length > 0);
      if (boxes.length !== expected.length) p.push(`charts: ${boxes.length} containers for ${expected.length} charts`);
      if (drawn.length !== expected.length) p.push(`charts: ${drawn.length} of ${expected.length} drawn`);
      for (const id of expected) if (!document.getElementById('chart-' + id)) p.push(`chart ${id}: no container`);
      // Images: embedded (no file:// fetches) and decoded.
      const imgs = [...document.querySelectorAll('img')];
      if (imgs.length === 0) p.push('images: none in the page');
      for (const img of imgs) {
        const where = (img.closest('figure') || {}).id || '(outside a strip)';
        if (!img.src.startsWith('data:image/png;base64,')) p.push(`image ${where} ${img.alt}: not embedded`);
        else if (!(img.complete && img.naturalWidth > 0)) p.push(`image ${where} ${img.alt}: not loaded`);
      }
      // Worst frames the report names without an image.
      for (const s of document.querySelectorAll('.no-image'))
        p.push(`worst frame missing: ${s.dataset.case} frame ${s.dataset.frame}`);
      // Every in-page link (worst frames -> strips, grid -> scenario rows) has its target; a strip
      // a worst frame links to has images that loaded.
      for (const a of document.querySelectorAll('a[href^="#"]:not([href="#"])')) {  // vega-embed's menu: "#"
        const id = decodeURIComponent(a.getAttribute('href').slice(1));
        const target = document.getElementById(id);
        if (!target) { p.push(`link #${id}: no target`); continue; }
        if (id.startsWith('img-')) {
          const shots = [...target.querySelectorAll('img')];
          if (!shots.length || shots.some((i) => !(i.naturalWidth > 0))) p.push(`worst frame ${id}: images not loaded`);
        }
      }
      // The page fits the window: wide tables scroll inside their own box.
      const w = document.documentElement.scrollWidth;
      if (w > window.innerWidth) p.push(`page ${w} px wide in a ${window.innerWidth} px window`);
      return p;
    }, manifest.charts.map((c) => c.id));
    problems.push(...found);
    if (screenshot) {
      // Whole page when Chromium can capture it in one go; else the first screen (scenario runs with
      // hundreds of strips are 200,000 px tall).
      const tall = await page.evaluate(() => document.documentElement.scrollHeight);
      await page.screenshot({path: screenshot, fullPage: tall <= 16384});
      console.log(`screenshot: ${screenshot}`);
    }
  } finally {
    await page.close();
  }
  return {problems, page, manifest};
}

async function tables(reportDir) {
  const page = await browser.newPage();
  await page.goto(pathToFileURL(path.join(reportDir, 'report.html')).href);
  const t = await page.$$eval('table', (els) => els.map((e) => e.className));
  await page.close();
  return t;
}

// Worst frames of the fixture (summary worst_frames whose metric went wrong) without a PNG.
function fixtureWorstWithoutImages(run) {
  const missing = [];
  for (const f of fs.readdirSync(path.join(run, 'cases'))) {
    const c = JSON.parse(fs.readFileSync(path.join(run, 'cases', f), 'utf8'));
    const s = c.summary || {};
    const frames = new Set();
    for (const key of ['cracks_pixels', 'pop_mean', 'err_p95_px'])
      if (s[key] && s[key].max > 0 && Number.isInteger((s.worst_frames || {})[key])) frames.add(s.worst_frames[key]);
    for (const fr of frames) {
      const any = fs.readdirSync(path.join(run, 'images')).some((n) => n.startsWith(`${c.case_id}_f${fr}_`));
      if (!any) missing.push(`worst frame missing: ${c.case_id} frame ${fr}`);
    }
  }
  return missing.sort();
}

test('the fixture report draws every chart and image, and names exactly its worst frames without images', async () => {
  const run = copyRun(fixture, 'fixture');
  lodbench('report', run);
  const dir = path.join(run, 'report');
  const {problems, manifest} = await inspect(dir, path.join(out, 'fixture.png'));
  assert.ok(manifest.charts.length >= 6, `expected the six fixture charts, got ${manifest.charts.length}`);
  for (const c of manifest.charts) assert.ok(fs.statSync(path.join(dir, 'svg', c.id + '.svg')).size > 1000, c.id);
  // The fixture keeps images of two frames only: its other worst frames are the planted defect.
  const expected = fixtureWorstWithoutImages(run);
  assert.ok(expected.length > 0, 'the fixture has worst frames without images');
  const worstMissing = [...new Set(problems.filter((p) => p.startsWith('worst frame missing')))].sort();
  assert.deepEqual(worstMissing, expected);
  assert.deepEqual(problems.filter((p) => !p.startsWith('worst frame missing')), []);
  for (const t of ['context', 'stability sticky', 'problems', 'cases sticky'])
    assert.ok((await tables(dir)).includes(t), `${t} table`);
  // Click to enlarge: the viewer shows the same image larger than its strip, Escape closes it.
  const page = await browser.newPage();
  await page.goto(pathToFileURL(path.join(dir, 'report.html')).href);
  const shot = page.locator('.shot img').first();
  const small = (await shot.boundingBox()).width;
  await shot.click();
  const big = await page.locator('#zoom img').boundingBox();
  assert.ok(big.width > small, `enlarged ${big.width} px > ${small} px`);
  assert.equal(await page.locator('#zoom img').getAttribute('src'), await shot.getAttribute('src'));
  await page.keyboard.press('Escape');
  assert.equal(await page.locator('#zoom').count(), 0);
  await page.close();
});

test('a planted missing image fails the check', async () => {
  const run = copyRun(fixture, 'planted');
  lodbench('report', run, '--no-html');
  const victim = fs.readdirSync(path.join(run, 'images')).filter((n) => n.endsWith('.png')).sort()[0];
  fs.rmSync(path.join(run, 'images', victim));  // after body.html names it, before render.mjs embeds it
  execFileSync(process.execPath, [path.join(root, 'report/render.mjs'), path.join(run, 'report')], {stdio: 'inherit'});
  const {problems} = await inspect(path.join(run, 'report'));
  const anchor = 'img-' + victim.replace(/_[a-z]+\.png$/, '').replace(/_f(\d+)$/, '-f$1');
  assert.equal(problems.filter((p) => p.startsWith(`image ${anchor} `)).length, 1,
               `missing ${victim} not reported: ${problems.join('; ')}`);
  // Nothing else is new: only the fixture's known worst frames without images, and the missing one.
  assert.deepEqual(problems.filter((p) => !p.startsWith('worst frame missing') && !p.includes(anchor)), []);
});

test('a small lavapipe scenario run: every worst frame imaged, grid and scenario rows linked, nothing wrong', async () => {
  let run = process.env.REPORT_TEST_RUN;
  if (!run) {
    run = path.join(out, 'run');
    lodbench('run', path.join(root, 'tests/configs/report_browser.json'), '--out', run, '--quiet');
  }
  run = copyRun(run, 'checked');
  lodbench('report', run);
  const dir = path.join(run, 'report');
  const {problems} = await inspect(dir, path.join(out, 'run.png'));
  assert.deepEqual(problems, []);
  const t = await tables(dir);
  for (const want of ['context', 'stability sticky', 'cases sticky']) assert.ok(t.includes(want), `${want} table`);
  if (!process.env.REPORT_TEST_RUN) {
    assert.ok(t.includes('grid sticky') && t.includes('scenario sticky'), `scenario grid and rows: ${t}`);
    const md = fs.readFileSync(path.join(dir, 'report.md'), 'utf8');
    assert.match(md, /Fastest at a mean screen-space error of at most /);
    assert.match(md, /Most accurate within /);
  }
});
