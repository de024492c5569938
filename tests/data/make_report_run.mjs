// Builds the report fixture tests/data/report_run/ from a real lavapipe run plus synthetic
// measurement metrics. Why synthetic: the fixture must exercise every field of
// docs/results-format.md (histograms, error, cracks, popping, saturation) and the degraded cases
// (timing-only, failed, skipped) with a few frames, without a GPU in the test.
//
//   build/lodbench run <config with uniform/sphere/phong x flyover/lowalt, 96x54, 8 frames> --out /tmp/fixrun
//   node tests/data/make_report_run.mjs /tmp/fixrun tests/data/report_run
//
// Counters, timings and images come from the real run; metrics follow a simple model (log-normal
// triangle areas around the scheme's mean area, error growing with triangle size).
import fs from 'node:fs';
import path from 'node:path';

const [src, dst] = process.argv.slice(2);
if (!src || !dst) throw new Error('usage: make_report_run.mjs <real-run-dir> <fixture-dir>');

let seed = 12345;
const rand = () => {  // mulberry32: deterministic, so the fixture is reproducible
  seed = (seed + 0x6d2b79f5) | 0;
  let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
  t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
  return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
};
const jitter = (x, f) => x * (1 + f * (2 * rand() - 1));
const erf = (x) => {  // Abramowitz-Stegun 7.1.26
  const s = Math.sign(x), a = Math.abs(x), t = 1 / (1 + 0.3275911 * a);
  const y = 1 - ((((1.061405429 * t - 1.453152027) * t + 1.421413741) * t - 0.284496736) * t + 0.254829592) * t * Math.exp(-a * a);
  return s * y;
};
const cdf = (x, mu, sigma) => 0.5 * (1 + erf((Math.log(x) - mu) / (sigma * Math.SQRT2)));
const round = (x, d = 4) => Number(x.toFixed(d));

function percentile(v, q) {  // numpy's linear interpolation, as harness/stats.cpp
  const s = [...v].sort((a, b) => a - b);
  const pos = (q / 100) * (s.length - 1), lo = Math.floor(pos), hi = Math.min(lo + 1, s.length - 1);
  return s[lo] + (s[hi] - s[lo]) * (pos - lo);
}
function stats(v) {
  if (!v.length) return null;
  const mean = v.reduce((a, b) => a + b, 0) / v.length;
  const sd = Math.sqrt(v.reduce((a, b) => a + (b - mean) ** 2, 0) / v.length);
  return {median: percentile(v, 50), p5: percentile(v, 5), p95: percentile(v, 95), p99: percentile(v, 99), mean,
          min: Math.min(...v), max: Math.max(...v), stddev: sd};
}

const kSigma = {uniform: 1.3, sphere: 0.55, phong: 0.65};
const kErrFactor = {uniform: 1.6, sphere: 1.0, phong: 0.8};
const kPop = {uniform: 0, sphere: 0.4, phong: 0.7};
const kTimingOnly = 'sphere-tri_size8_proc129s1_lowalt_96x54';
const kFailed = 'phong-tri_size8_proc129s1_lowalt_96x54';
const kKeepImages = ['sphere-tri_size2_proc129s1_flyover_96x54_f0_', 'phong-tri_size4_proc129s1_lowalt_96x54_f6_'];
const metricKeys = ['tri_area_mean', 'tri_frac_under_1px', 'tri_frac_near_target', 'err_mean_px', 'err_p95_px',
                    'err_max_px', 'img_psnr_db', 'img_ssim', 'img_mad', 'img_frac_over', 'cracks_analytic',
                    'cracks_pixels', 'pop_mean', 'pop_p99', 'pop_changed', 'surplus'];

function targetArea(c) {
  const t = c.params.tri_size;
  if (c.scheme === 'sphere') return t * t / 2;                 // half of a t x t pixel square
  if (c.scheme === 'phong') return t * t * Math.sqrt(3) / 4;   // equilateral triangle with edge t
  return null;
}

function measure(c, f, lowalt) {
  const [w, h] = c.resolution;
  const off = jitter(lowalt ? 0.45 : 0.3, 0.1), back = jitter(0.04, 0.2);
  const offscreen = Math.round(f.clip_invocations * off), backfacing = Math.round(f.clip_invocations * back);
  const on = f.clip_invocations - offscreen - backfacing;
  const sigma = kSigma[c.scheme];
  const meanArea = (w * h * (lowalt ? 0.7 : 0.85) * 1.15) / on;
  const mu = Math.log(meanArea) - sigma * sigma / 2;
  const hist = [];
  let prev = 0;
  for (let i = 0; i < 14; i++) {
    const upper = on * cdf(2 ** (i - 3), mu, sigma);
    hist.push(Math.round(upper) - Math.round(prev));
    prev = upper;
  }
  hist.push(on - hist.reduce((a, b) => a + b, 0));
  const target = targetArea(c);
  const err = jitter(0.4 * Math.exp(mu / 2) * kErrFactor[c.scheme] * (lowalt ? 1.4 : 1), 0.1);
  const p95 = err * jitter(3.2, 0.1);
  const mad = err * 4;
  const phong = c.scheme === 'phong';
  const level = c.params.level;
  return {
    hist, hist_offscreen: offscreen, hist_backfacing: backfacing,
    tri_area_mean: round(meanArea), tri_area_median: round(Math.exp(mu)),
    tri_frac_under_1px: round(cdf(1, mu, sigma)),
    tri_frac_near_target: target === null ? null : round(cdf(2 * target, mu, sigma) - cdf(target / 2, mu, sigma)),
    err_mean_px: round(err), err_p95_px: round(p95), err_max_px: round(p95 * jitter(2.2, 0.1)),
    img_psnr_db: round(20 * Math.log10(255 / (mad * 1.8 + 0.5)), 3), img_ssim: round(1 - 0.02 * err * 4),
    img_mad: round(mad), img_frac_over: round(Math.min(1, 0.015 * err * 4)),
    // phong's lowalt cracks grow along the path, so the worst frame (6) is one with images.
    cracks_analytic: !phong ? 0 : lowalt ? 1 + Math.floor(f.frame / 2) : Math.floor(rand() * 2),
    cracks_pixels: !phong ? 0 : lowalt ? 2 + Math.round(f.frame * 1.5) : Math.floor(rand() * 3),
    pop_mean: round(jitter(kPop[c.scheme], 0.4)), pop_p99: round(jitter(kPop[c.scheme] * 20, 0.3), 2),
    pop_changed: Math.round(jitter(kPop[c.scheme] * 300, 0.4)),
    surplus: round(jitter(c.scheme === 'uniform' ? level * level / 60 : 1 + 1 / (c.params.tri_size || 1), 0.05), 3),
  };
}

function summarize(c, frames, saturated) {
  const pick = (k, fs = frames) => fs.map((f) => f[k]).filter((x) => x !== null && x !== undefined);
  const gpu = stats(pick('gpu_ms'));
  const s = {frames: frames.length, gpu_ms: gpu, cpu_ms: stats(pick('cpu_ms')), fps_median: 1000 / gpu.median,
             fps_mean: 1000 / gpu.mean, triangles: stats(pick('clip_invocations')), patches: stats(pick('patches')),
             tes_invocations: stats(pick('tes_invocations')), fragment_invocations: stats(pick('fragment_invocations'))};
  const measured = frames.filter((f) => 'hist' in f);
  if (!measured.length) return s;
  for (const k of metricKeys) s[k] = stats(pick(k, measured));
  s.hist_total = measured.reduce((t, f) => t.map((x, i) => x + f.hist[i]), new Array(15).fill(0));
  s.hist_offscreen_total = pick('hist_offscreen', measured).reduce((a, b) => a + b, 0);
  s.hist_backfacing_total = pick('hist_backfacing', measured).reduce((a, b) => a + b, 0);
  s.measured_frames = measured.length;
  const worst = (k) => measured.reduce((b, f) => (f[k] > b[k] ? f : b)).frame;
  s.worst_frames = {cracks_pixels: worst('cracks_pixels'), pop_mean: worst('pop_mean'), err_p95_px: worst('err_p95_px')};
  s.saturated_fraction = saturated;
  return s;
}

fs.rmSync(dst, {recursive: true, force: true});
fs.mkdirSync(path.join(dst, 'cases'), {recursive: true});
fs.mkdirSync(path.join(dst, 'images'), {recursive: true});
const run = JSON.parse(fs.readFileSync(path.join(src, 'run.json')));
const relPath = (p) => 'configs/paths/' + path.basename(p);
run.context.config_file = 'configs/report_fixture.json';
run.context.config.paths = run.context.config.paths.map((p) => 'paths/' + path.basename(p));
run.context.config.measure = {every: 2};
run.context.config.schemes.push({name: 'interlock', params: {}});

const cases = [];
for (const file of fs.readdirSync(path.join(src, 'cases')).sort()) {
  const c = JSON.parse(fs.readFileSync(path.join(src, 'cases', file)));
  const lowalt = c.path.includes('lowalt');
  c.path = relPath(c.path);
  c.target_area_px = targetArea(c);
  c.images = c.images.filter((img) => kKeepImages.some((k) => img.includes(k)));
  for (const img of c.images) fs.copyFileSync(path.join(src, img), path.join(dst, img));
  if (c.case_id === kFailed) {
    Object.assign(c, {status: 'failed', reason: 'vkQueueSubmit: VK_ERROR_DEVICE_LOST at frame 5', frames: [], summary: {}});
  } else {
    if (c.case_id !== kTimingOnly)
      for (const f of c.frames) if (f.frame % 2 === 0) Object.assign(f, measure(c, f, lowalt));
    const saturated = c.scheme === 'sphere' && c.params.tri_size === 2 && lowalt ? 0.5 : 0;
    c.summary = summarize(c, c.frames, saturated);
  }
  cases.push(c);
}
for (const p of run.context.config.paths) {
  const id = `interlock_proc129s1_${path.basename(p, '.csv')}_96x54`;
  cases.push({schema_version: 1, case_id: id, scheme: 'interlock', params: {}, terrain: cases[0].terrain,
              path: relPath(p), resolution: [96, 54], status: 'skipped',
              reason: 'quad12 patches need maxTessellationPatchSize >= 12, device has 4', seconds: 0, images: [],
              target_area_px: null, summary: {}, frames: []});
}
for (const c of cases) fs.writeFileSync(path.join(dst, 'cases', c.case_id + '.json'), JSON.stringify(c, null, 1) + '\n');

const count = (s) => cases.filter((c) => c.status === s).length;
run.totals = {cases: cases.length, ok: count('ok'), failed: count('failed'), skipped: count('skipped')};
fs.writeFileSync(path.join(dst, 'run.json'), JSON.stringify(run, null, 1) + '\n');
const summary = {schema_version: 1, context: run.context,
                 cases: cases.map((c) => ({case_id: c.case_id, scheme: c.scheme, params: c.params, terrain: c.terrain.label,
                                           path: c.path, resolution: c.resolution, status: c.status, reason: c.reason,
                                           summary: c.summary}))};
fs.writeFileSync(path.join(dst, 'summary.json'), JSON.stringify(summary, null, 1) + '\n');

const cols = ['gpu_ms', 'cpu_ms', 'patches', 'tes_invocations', 'clip_invocations', 'clip_primitives', 'fragment_invocations'];
const mcols = [...Array(15).keys()].map((i) => 'hist_' + i).concat(['hist_offscreen', 'hist_backfacing', 'tri_area_mean',
  'tri_area_median', 'tri_frac_under_1px', 'tri_frac_near_target', 'err_mean_px', 'err_p95_px', 'err_max_px', 'img_psnr_db',
  'img_ssim', 'img_mad', 'img_frac_over', 'cracks_analytic', 'cracks_pixels', 'pop_mean', 'pop_p99', 'pop_changed', 'surplus']);
let csv = ['case_id', 'frame', ...cols, ...mcols].join(',') + '\n';
for (const c of cases)
  for (const f of c.frames) {
    const m = mcols.map((k) => (k.startsWith('hist_') && /\d$/.test(k) ? f.hist?.[+k.slice(5)] : f[k]) ?? '');
    csv += [c.case_id, f.frame, ...cols.map((k) => f[k]), ...m].join(',') + '\n';
  }
fs.writeFileSync(path.join(dst, 'frames.csv'), csv);
