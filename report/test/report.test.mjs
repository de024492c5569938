// Browser test of report.html: `lodbench report`, then Debian's
// chromium (through playwright-core, never a downloaded browser) opens the page from file://
// offline and checks: report.html at most 10 MB, no console errors or warnings, every chart drawn
// (vega views rendered = charts in the manifest), every image linked (not embedded) and loaded
// once scrolled into view (naturalWidth > 0), every worst frame the report names present with its
// images, every in-page link resolving, and no section of the page wider than 1,400 px. The check
// itself is tested: a planted missing image and the fixture's worst frames without images must be
// reported. The lavapipe run is tests/configs/report_browser.json (seconds); the default job
// (configs/quick.json, minutes) is checked the same way with REPORT_TEST_RUN=<its run dir>.
//   LODBENCH_BINARY   the lodbench executable (default build/lodbench)
//   CHROMIUM          the browser (default /usr/bin/chromium)
//   REPORT_TEST_OUT   where the reports and screenshots go (default: a fresh temp dir)
//   REPORT_TEST_RUN   a run directory to check instead of making the small lavapipe run
import {test, before, after} from 'node:test';
import assert from 'node:assert/strict';
import {execFileSync, spawnSync} from 'node:child_process';
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
const kMaxBytes = 10e6;  // report.html of a linked report, the default job's included

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
async function inspect(reportDir, screenshot, {embedded = false} = {}) {
  const manifest = JSON.parse(fs.readFileSync(path.join(reportDir, 'manifest.json'), 'utf8'));
  const page = await browser.newPage();
  const problems = [];
  const bytes = fs.statSync(path.join(reportDir, 'report.html')).size;
  if (!embedded && bytes > kMaxBytes) problems.push(`report.html is ${bytes} bytes, over ${kMaxBytes}`);
  // Vega reports spec problems as console warnings: treat them like errors.
  page.on('console', (m) => { if (['error', 'warning'].includes(m.type())) problems.push(`console ${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push('page error: ' + e.message));
  // Only local files and inline data: the page must open offline.
  page.on('request', (r) => { if (!/^(file|data|about|blob):/.test(r.url())) problems.push('external request: ' + r.url()); });
  try {
    await page.goto(pathToFileURL(path.join(reportDir, 'report.html')).href);
    await page.waitForFunction(() => document.body.dataset.charts, null, {timeout: 30000});
    const state = await page.evaluate(() => document.body.dataset.charts);
    if (state !== 'done') problems.push(`charts: ${state}`);
    const found = await page.evaluate(async ({expected, embedded, maxWidth}) => {
      const p = [];
      // Charts: one container per manifest chart, each with one drawn Vega view holding data marks.
      const boxes = [...document.querySelectorAll('.chart')];
      const drawn = boxes.filter((el) => el.querySelectorAll('svg.marks').length === 1 &&
        el.querySelectorAll('svg.marks g.role-mark > path, svg.marks g.role-mark > rect, svg.marks g.role-mark > text').length > 0);
      if (boxes.length !== expected.length) p.push(`charts: ${boxes.length} containers for ${expected.length} charts`);
      if (drawn.length !== expected.length) p.push(`charts: ${drawn.length} of ${expected.length} drawn`);
      for (const id of expected) if (!document.getElementById('chart-' + id)) p.push(`chart ${id}: no container`);
      // Images: linked files, lazily loaded (or embedded with --self-contained); each one loads once
      // scrolled into view.
      const imgs = [...document.querySelectorAll('img')];
      if (imgs.length === 0) p.push('images: none in the page');
      const loaded = (img) => new Promise((resolve) => {
        if (img.complete) return resolve();
        img.addEventListener('load', resolve, {once: true});
        img.addEventListener('error', resolve, {once: true});
        setTimeout(resolve, 5000);
      });
      for (const img of imgs) {
        const where = (img.closest('figure') || img.closest('.side-grid, .flip') || {}).id ||
                      (img.closest('.side-grid') ? 'side-by-side' : '(outside a strip)');
        const file = decodeURIComponent((img.getAttribute('src') || '').split('/').pop()).slice(0, 120);
        const src = img.getAttribute('src') || '';
        if (embedded !== src.startsWith('data:image/png;base64,'))
          p.push(`image ${where} ${img.alt}: ${embedded ? 'not embedded' : 'embedded, not linked'}`);
        if (!embedded && img.getAttribute('loading') !== 'lazy') p.push(`image ${where} ${img.alt}: not lazy (${file})`);
        img.scrollIntoView();
        await loaded(img);
        if (!(img.complete && img.naturalWidth > 0)) p.push(`image ${where} ${img.alt}: not loaded (${file})`);
      }
      window.scrollTo(0, 0);
      // Worst frames the report names without an image.
      for (const s of document.querySelectorAll('.no-image[data-case]'))
        p.push(`worst frame missing: ${s.dataset.case} frame ${s.dataset.frame}`);
      // Every in-page link (worst frames -> strips, grid -> scenario rows, headers -> definitions)
      // has its target; a strip a worst frame links to has images that loaded.
      for (const a of document.querySelectorAll('a[href^="#"]:not([href="#"])')) {  // vega-embed's menu: "#"
        const id = decodeURIComponent(a.getAttribute('href').slice(1));
        const target = document.getElementById(id);
        if (!target) { p.push(`link #${id}: no target`); continue; }
        if (id.startsWith('img-')) {
          const shots = [...target.querySelectorAll('img')];
          if (!shots.length || shots.some((i) => !(i.naturalWidth > 0))) p.push(`worst frame ${id}: images not loaded`);
        }
      }
      // Every section fits 1,400 px: each block's right edge, its own content included (a chart
      // wider than its box), except boxes that scroll their content (wide tables).
      let section = '(top)';
      for (const el of document.body.children) {
        if (el.tagName === 'H2') section = el.id;
        const style = getComputedStyle(el);
        if (style.display === 'none' || style.position === 'fixed' || el.tagName === 'SCRIPT') continue;
        const r = el.getBoundingClientRect();
        const scrolls = ['auto', 'scroll', 'hidden'].includes(style.overflowX);
        const right = r.left + window.scrollX + (scrolls ? r.width : Math.max(r.width, el.scrollWidth));
        if (right > maxWidth + 0.5) p.push(`section ${section}: ${el.tagName.toLowerCase()}.${el.className} reaches ${Math.round(right)} px`);
      }
      const w = document.documentElement.scrollWidth;
      if (w > maxWidth) p.push(`page ${w} px wide, over ${maxWidth} px`);
      return p;
    }, {expected: manifest.charts.map((c) => c.id), embedded, maxWidth: kWidth});
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
  return {problems, page, manifest, bytes};
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
  assert.equal(await page.$eval('#zoom img', (i) => i.src), await shot.evaluate((i) => i.src));
  await page.keyboard.press('Escape');
  assert.equal(await page.locator('#zoom').count(), 0);
  await page.close();
});

test('a planted missing image fails the check', async () => {
  const run = copyRun(fixture, 'planted');
  lodbench('report', run);
  const victim = fs.readdirSync(path.join(run, 'images')).filter((n) => n.endsWith('.png')).sort()[0];
  fs.rmSync(path.join(run, 'images', victim));  // the page links it: the browser finds it missing
  const {problems} = await inspect(path.join(run, 'report'));
  const anchor = 'img-' + victim.replace(/_[a-z]+\.png$/, '').replace(/_f(\d+)$/, '-f$1');
  assert.equal(problems.filter((p) => p.startsWith(`image ${anchor} `) && p.endsWith(`not loaded (${victim})`)).length, 1,
               `missing ${victim} not reported: ${problems.join('; ')}`);
  // Nothing else is new: only the fixture's known worst frames without images, and the missing one.
  // Chromium logs the failed fetch of that file too; nothing else may be new.
  const known = (p) => p.startsWith('worst frame missing') || p.includes(victim) || p.includes(anchor) ||
                       p === 'console error: Failed to load resource: net::ERR_FILE_NOT_FOUND';
  assert.deepEqual(problems.filter((p) => !known(p)), []);
});

test('a section wider than 1,400 px fails the check', async () => {
  const run = copyRun(fixture, 'wide');
  lodbench('report', run, '--no-html');
  const body = path.join(run, 'report', 'body.html');
  fs.writeFileSync(body, fs.readFileSync(body, 'utf8').replace('<h2 id="context">Context</h2>\n',
    '<h2 id="context">Context</h2>\n<div class="planted" style="width: 2000px">too wide</div>\n'));
  execFileSync(process.execPath, [path.join(root, 'report/render.mjs'), path.join(run, 'report')], {stdio: 'inherit'});
  const {problems} = await inspect(path.join(run, 'report'));
  assert.ok(problems.some((p) => /^section context: div\.planted reaches 20\d\d px$/.test(p)), problems.join('; '));
});

test('--self-contained embeds every image in one file and says its size', async () => {
  const run = copyRun(fixture, 'self-contained');
  const said = spawnSync(binary, ['report', run, '--self-contained'], {encoding: 'utf8'});
  assert.equal(said.status, 0, said.stderr);
  const dir = path.join(run, 'report');
  const {problems, bytes} = await inspect(dir, null, {embedded: true});
  assert.deepEqual(problems.filter((p) => !p.startsWith('worst frame missing')), []);
  // Every image is in the page itself: the run's images/ can go and the page still shows them all.
  const pngs = fs.readdirSync(path.join(run, 'images')).filter((n) => n.endsWith('.png'));
  assert.ok(bytes > pngs.reduce((n, f) => n + fs.statSync(path.join(run, 'images', f)).size, 0));
  fs.rmSync(path.join(run, 'images'), {recursive: true});
  const again = await inspect(dir, null, {embedded: true});
  assert.deepEqual(again.problems.filter((p) => !p.startsWith('worst frame missing')), []);
  // It says the size it wrote.
  assert.match(said.stderr, new RegExp(`report\\.html is [0-9.]+ MB \\(${bytes} bytes\\), self-contained`));
});

test('a small lavapipe scenario run (or REPORT_TEST_RUN): every image loads, every section fits, the flip flips', async () => {
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
    // One repetition: the margin is given, with no spread to judge it by.
    assert.match(md, /a margin of [0-9.]+ ms \([0-9.-]+%\); the run has one repetition, so there is no run-to-run spread/);
  }
  // Side by side: a row per scheme at one frame; the flip shows scheme A, then B, in the chosen mode.
  const page = await browser.newPage();
  await page.goto(pathToFileURL(path.join(dir, 'report.html')).href);
  const schemes = await page.$$eval('.side-label b', (els) => els.map((e) => e.textContent));
  if (!process.env.REPORT_TEST_RUN) assert.deepEqual(schemes, ['uniform', 'sphere']);
  const [a, b] = schemes;
  const shown = () => page.$eval('#flip img', (i) => i.src);
  const gridSrc = (scheme, mode) =>
    page.$eval(`.side-grid img[data-scheme="${scheme}"][data-mode="${mode}"]`, (i) => i.src);
  assert.equal(await page.inputValue('#flip-a'), a);
  assert.equal(await page.inputValue('#flip-b'), b);
  assert.equal(await shown(), await gridSrc(a, 'shaded'));
  await page.click('#flip-button');
  assert.equal(await shown(), await gridSrc(b, 'shaded'));
  await page.selectOption('#flip-mode', 'error');
  assert.equal(await shown(), await gridSrc(b, 'error'));
  await page.keyboard.press('f');
  assert.equal(await shown(), await gridSrc(a, 'error'));
  assert.equal(await page.textContent('#flip-showing'), a);
  await page.close();
});
