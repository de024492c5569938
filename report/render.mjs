// Renders a report directory written by `lodbench report` (manifest.json, body.html, charts/*.vl.json,
// data/*.json) into
//   report.html  one self-contained page: Vega, Vega-Lite and vega-embed inlined, chart specs with
//                their data inlined, images embedded as data: URIs; opens offline.
//   svg/<id>.svg each chart drawn headless in Node (vega's View.toSVG), for papers.
//   png/<id>.png the same SVG rasterized at 2x by Debian's chromium through playwright-core (vega's
//                toCanvas would need node-canvas, a native module we do not install); without
//                chromium or playwright-core, png/MISSING.txt says why and the page still renders.
// Usage: node report/render.mjs <report-dir>     (set up once: bash scripts/install-report-deps.sh)
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import {fileURLToPath} from 'node:url';
import * as vega from 'vega';
import * as vl from 'vega-lite';

const here = path.dirname(fileURLToPath(import.meta.url));
const dir = process.argv[2];
if (!dir) {
  console.error('usage: node report/render.mjs <report-dir>');
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

// Replaces every {"url": "data/x.json"} data source by its values, so a spec stands alone.
function inlineData(node) {
  if (Array.isArray(node)) return node.forEach(inlineData);
  if (!node || typeof node !== 'object') return;
  if (node.data && typeof node.data.url === 'string') node.data = {values: JSON.parse(read(node.data.url))};
  Object.values(node).forEach(inlineData);
}

// Inline <script> and JSON must not contain "</script" (it would end the element early).
const scriptSafe = (text) => text.replace(/<\/(script)/gi, '<\\/$1');
const jsonSafe = (value) => JSON.stringify(value).replace(/</g, '\\u003c');

function embedImages(html) {
  return html.replace(/<img src="([^"]+)"/g, (tag, src) => {
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
for (const chart of manifest.charts) {
  const spec = JSON.parse(read(chart.spec));
  inlineData(spec);
  specs[chart.id] = spec;
}

fs.mkdirSync(path.join(dir, 'svg'), {recursive: true});
for (const [id, spec] of Object.entries(specs)) {
  const view = new vega.View(vega.parse(vl.compile(spec, {config}).spec), {renderer: 'none'});
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
const body = embedImages(read('body.html'));
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
       max-width: 1500px; }
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
const config = ${jsonSafe(config)};
const actions = {export: true, source: false, compiled: false, editor: false};
Promise.all(Object.entries(specs).map(([id, spec]) =>
  vegaEmbed('#chart-' + id, spec, {renderer: 'svg', config, actions}).catch((e) => {
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
console.error(`render.mjs: ${path.join(dir, 'report.html')} (${(html.length / 1e6).toFixed(1)} MB), ` +
              `${Object.keys(specs).length} SVGs in ${path.join(dir, 'svg')}` +
              (pngMissing ? '' : `, PNGs in ${path.join(dir, 'png')}`));
