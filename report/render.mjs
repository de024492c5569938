// Renders a report directory written by `lodbench report` (manifest.json, body.html, charts/*.vl.json,
// data/*.json) into
//   report.html  the page: Vega, Vega-Lite and vega-embed inlined, chart specs with their data
//                inlined; run images linked where they lie (the run folder's images/, lazily loaded),
//                so the page stays small and every image is stored once. With --self-contained the
//                images are embedded as data: URIs instead: one file that opens anywhere, offline.
//   svg/<id>.svg each chart drawn headless in Node (vega's View.toSVG), for papers.
//   png/<id>.png the same SVG rasterized at 2x by Debian's chromium through playwright-core (vega's
//                toCanvas would need node-canvas, a native module we do not install); without
//                chromium or playwright-core, png/MISSING.txt says why and the page still renders.
// Usage: node report/render.mjs <report-dir> [--self-contained]
//        (set up once: bash scripts/install-report-deps.sh)
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {fileURLToPath} from 'node:url';
import * as vega from 'vega';
import * as vl from 'vega-lite';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = process.argv.slice(2);
const selfContained = args.includes('--self-contained');
const dir = args.find((a) => !a.startsWith('--'));
const unknown = args.filter((a) => a.startsWith('--') && a !== '--self-contained');
if (!dir || unknown.length) {
  console.error(`usage: node report/render.mjs <report-dir> [--self-contained]${unknown.length ? ` (unknown option ${unknown[0]})` : ''}`);
  process.exit(2);
}

// One look for every chart, in the page and in the SVGs.
const config = {
  background: 'white',
  font: 'DejaVu Sans, Helvetica, Arial, sans-serif',
  title: {fontSize: 16, subtitleFontSize: 12, subtitleColor: '#555', anchor: 'start', offset: 10},
  axis: {titleFontSize: 12, labelFontSize: 11, titleFontWeight: 'normal'},
  header: {titleFontSize: 13, labelFontSize: 12},
  legend: {titleFontSize: 12, labelFontSize: 11},
  view: {stroke: '#ccc'},
};

const read = (file) => fs.readFileSync(path.join(dir, file), 'utf8');

// Replaces every {"url": "data/x.json"} data source by a named one whose values are written once into the
// page (the three timelines share one data file), so a spec stands alone with its datasets.
const datasets = {};
function nameData(node, used) {
  if (Array.isArray(node)) return node.forEach((n) => nameData(n, used));
  if (!node || typeof node !== 'object') return;
  if (node.data && typeof node.data.url === 'string') {
    const name = node.data.url;
    datasets[name] ??= JSON.parse(read(name));
    used.add(name);
    node.data = {name};
  }
  Object.values(node).forEach((n) => nameData(n, used));
}

// Inline <script> and JSON must not contain "</script" (it would end the element early).
const scriptSafe = (text) => text.replace(/<\/(script)/gi, '<\\/$1');
const jsonSafe = (value) => JSON.stringify(value).replace(/</g, '\\u003c');

function embedImages(html) {
  // loading="lazy" does not matter for data: URIs; the attribute stays harmless.
  return html.replace(/<img src="([^"]+)"/g, (tag, src) => {  // imageTag() writes src first
    if (src.startsWith('data:')) return tag;
    const file = path.isAbsolute(src) ? src : path.join(dir, src.replace(/&amp;/g, '&'));
    if (!fs.existsSync(file)) {
      console.error(`render.mjs: image missing, left out: ${file}`);
      return '<img class="missing" alt="missing image"';
    }
    return `<img src="data:image/png;base64,${fs.readFileSync(file).toString('base64')}"`;
  });
}

const manifest = JSON.parse(read('manifest.json'));
const specs = {};
const specData = {};  // chart id -> the dataset names its spec uses
for (const chart of manifest.charts) {
  const spec = JSON.parse(read(chart.spec));
  const used = new Set();
  nameData(spec, used);
  specs[chart.id] = spec;
  specData[chart.id] = [...used];
}
const withData = (id) =>
  ({...specs[id], datasets: Object.fromEntries(specData[id].map((name) => [name, datasets[name]]))});

fs.mkdirSync(path.join(dir, 'svg'), {recursive: true});
for (const id of Object.keys(specs)) {
  const view = new vega.View(vega.parse(vl.compile(withData(id), {config}).spec), {renderer: 'none'});
  fs.writeFileSync(path.join(dir, 'svg', `${id}.svg`), await view.toSVG());
  view.finalize();
}

// Print resolution: 2 device pixels per CSS pixel.
async function writePngs(ids) {
  const pngDir = path.join(dir, 'png');
  fs.mkdirSync(pngDir, {recursive: true});
  fs.rmSync(path.join(pngDir, 'MISSING.txt'), {force: true});
  let chromium;
  try {
    ({chromium} = await import('playwright-core'));
  } catch (e) {
    return `playwright-core is not installed (${e.code || e.message}); run bash scripts/install-report-deps.sh`;
  }
  const exe = [process.env.CHROMIUM, '/usr/bin/chromium', '/usr/bin/chromium-browser'].find((p) => p && fs.existsSync(p));
  if (!exe) return 'no chromium at $CHROMIUM, /usr/bin/chromium or /usr/bin/chromium-browser';
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'lodbench-png-'));
  const browser = await chromium.launchPersistentContext(profile, {
    executablePath: exe, headless: true, deviceScaleFactor: 2,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run', '--disable-background-networking',
           '--disable-component-update', '--disable-sync']});
  try {
    const page = await browser.newPage();
    for (const id of ids) {
      const svg = fs.readFileSync(path.join(dir, 'svg', `${id}.svg`), 'utf8');
      await page.setContent(`<!DOCTYPE html><html><body style="margin:0;background:#fff">${svg}</body></html>`);
      await (await page.$('svg')).screenshot({path: path.join(pngDir, `${id}.png`)});
    }
  } finally {
    await browser.close();
    fs.rmSync(profile, {recursive: true, force: true});
  }
  return '';
}

const pngMissing = await writePngs(Object.keys(specs)).catch((e) => `chromium failed: ${e.message.split('\n')[0]}`);
if (pngMissing) {
  fs.writeFileSync(path.join(dir, 'png', 'MISSING.txt'), `PNG charts not written: ${pngMissing}\n`);
  console.error(`render.mjs: PNG charts not written: ${pngMissing} (SVGs are complete)`);
}

const lib = (p) => scriptSafe(fs.readFileSync(path.join(here, 'node_modules', p), 'utf8'));
const body = selfContained ? embedImages(read('body.html')) : read('body.html');
const toc = [...body.matchAll(/<h2 id="([^"]+)">([^<]*)<\/h2>/g)]
  .map((m) => `<a href="#${m[1]}">${m[2]}</a>`)
  .join(' · ');

const html = `<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>${manifest.title.replace(/</g, '&lt;')}</title>
<style>
body { font: 14px/1.45 'DejaVu Sans', Helvetica, Arial, sans-serif; color: #222; margin: 0 auto; padding: 16px 24px;
       max-width: 1400px; box-sizing: border-box; }
h1 { font-size: 24px; margin: 8px 0; }
h2 { font-size: 19px; margin: 28px 0 8px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
nav { margin: 6px 0 12px; }
p.note { background: #fff8e1; border-left: 4px solid #f0b400; padding: 6px 10px; }
table { border-collapse: collapse; margin: 8px 0; font-size: 13px; }
th, td { border: 1px solid #ddd; padding: 3px 8px; text-align: left; vertical-align: top; }
th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tbody tr:nth-child(even) { background: #fafafa; }
table.cases { display: block; overflow-x: auto; font-size: 12px; }
code { font-size: 12px; }
figure { margin: 12px 0; }
figure.chart-box { border: 1px solid #eee; padding: 8px; display: inline-block; }
figcaption { color: #555; font-size: 12px; margin-top: 4px; }
.chart-files { font-size: 12px; margin-top: 4px; }
figure.strip { display: block; }
figure.strip figcaption { font-weight: bold; color: #222; font-size: 13px; margin: 0 0 4px; }
figure.strip:target { outline: 3px solid #f0b400; }
.shots { display: flex; flex-wrap: wrap; gap: 8px; }
.shot { display: flex; flex-direction: column; align-items: center; font-size: 12px; color: #555; }
.shot img { width: 288px; image-rendering: pixelated; border: 1px solid #ccc; }
pre { background: #f6f6f6; padding: 8px; max-height: 400px; overflow: auto; }
</style>
<script>${lib('vega/build/vega.min.js')}</script>
<script>${lib('vega-lite/build/vega-lite.min.js')}</script>
<script>${lib('vega-embed/build/vega-embed.min.js')}</script>
</head>
<body>
${body.replace('</h1>', '</h1>\n<nav>' + toc + '</nav>')}
<script>
const specs = ${jsonSafe(specs)};
const specData = ${jsonSafe(specData)};
const datasets = ${jsonSafe(datasets)};
const config = ${jsonSafe(config)};
const actions = {export: true, source: false, compiled: false, editor: false};
const withData = (id) =>
  ({...specs[id], datasets: Object.fromEntries(specData[id].map((name) => [name, datasets[name]]))});
Promise.all(Object.keys(specs).map((id) =>
  vegaEmbed('#chart-' + id, withData(id), {renderer: 'svg', config, actions}).catch((e) => {
    console.error('chart ' + id + ': ' + e);
    throw e;
  })))
  .then(() => { document.body.dataset.charts = 'done'; },
        () => { document.body.dataset.charts = 'failed'; });
</script>
</body>
</html>
`;
fs.writeFileSync(path.join(dir, 'report.html'), html);
const bytes = Buffer.byteLength(html);
const linked = (body.match(/<img src="(?!data:)/g) || []).length;
const images = (body.match(/<img /g) || []).length;
if (linked + (body.match(/<img src="data:/g) || []).length !== images)
  console.error(`render.mjs: ${images - linked} <img> without a leading src: not counted or embedded`);
console.error(`render.mjs: ${path.join(dir, 'report.html')} (${(bytes / 1e6).toFixed(1)} MB, ${bytes} bytes, ` +
              (selfContained ? 'self-contained: images embedded' : `${linked} images linked, not embedded`) + '), ' +
              `${Object.keys(specs).length} SVGs in ${path.join(dir, 'svg')}` +
              (pngMissing ? '' : `, PNGs in ${path.join(dir, 'png')}`));
