#include "replay/measure.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "error.h"
#include "metrics/coverage.h"
#include "metrics/cracks.h"
#include "metrics/flip.h"
#include "metrics/histogram_stats.h"
#include "metrics/mesh_cracks.h"
#include "render/image_io.h"
#include "replay/measure_gpu.h"
#include "replay/popping.h"
#include "schemes/registry.h"
#include "shaders/shared.h"
#include "stats.h"
#include "terrain/heightfield.h"

namespace lb {

static const double kNan = std::nan("");

// Patches whose largest captured level reached the partitioning's maximum.
static double saturatedPatches(const std::vector<float>& levels, Partitioning p) {
  float cap = p == Partitioning::FractionalOdd ? 63.0f : 64.0f;
  long n = 0;
  for (size_t i = 0; i + LB_CAPTURE_STRIDE <= levels.size(); i += LB_CAPTURE_STRIDE) {
    float m = 0;
    for (int k = 0; k < 6; ++k) m = std::max(m, levels[i + size_t(k)]);
    n += m >= cap;
  }
  return double(n);
}

// Crack pixels of the live frame against the truth; on the GPU path 0 without a read-back where no
// pixel meets crackPixels' local conditions (GpuImageStats::crackCandidates).
static long cracks(FrameMetrics& m, const GpuImageStats* gs, const RenderSettings& rs) {
  if (gs && gs->crackCandidates == 0) {
    m.crackMask.assign(size_t(rs.width) * size_t(rs.height), 0);
    return 0;
  }
  return crackPixels(m.shaded, m.reference, &m.crackMask);
}

// The CPU path's error statistics, as GpuReduce::errorStats reports them (exact here).
static GpuErrorStats errorStats(const std::vector<float>& map) {
  std::vector<double> e;
  for (float v : map)
    if (v >= 0) e.push_back(v);
  Summary s = summarize(e);
  if (e.empty()) return {0, kNan, kNan, kNan};
  return {long(e.size()), s.mean, s.p95, s.max};
}

FrameMetrics measureFrame(Context& ctx, Renderer& r, const Scheme& scheme, const ParamValues& params,
                          const Heightfield& terrain, const std::string& terrainKey, const MeasureSpec& spec,
                          ReferenceCache& refs, int frame, const CameraPose& previous, const CameraPose& current,
                          const RgbaImage* popBefore, bool keepPixels, const OlderLod* older) {
  FrameMetrics m;
  m.frame = frame;
  // Each pass's wall time, charged at the pass's end (lap): where a measured frame's time goes.
  auto last = std::chrono::steady_clock::now();
  auto lap = [&](const char* pass) {  // a pass that did not run (off) is not charged
    auto now = std::chrono::steady_clock::now();
    const std::string p = pass;
    if (spec.on(p) || p == "render" || p == "ray_cast" || (p == "flip" && spec.on("image")) ||
        (p == "setup" && now - last > std::chrono::microseconds(100)))
      m.costs[pass] += std::chrono::duration<double>(now - last).count();
    last = now;
  };
  auto set = [&](const std::string& k, double v) { m.values.emplace_back(k, v); };
  const RenderSettings& rs = r.settings();
  // On the GPU path (replay/measure_gpu.h) frames stay in device buffers and only numbers come back.
  MeasureGpu* g = measureOnGpu(spec, ctx) ? &refs.gpu(ctx, terrain, terrainKey, rs.width, rs.height) : nullptr;
  lap("setup");  // once per terrain and resolution: the GPU path's buffers, pyramid and pipelines
  // Live frame with factor capture: the basis for image metrics, cracks and saturation.
  FrameResult live;
  if (g)
    r.renderInto(current, current, RenderMode::Shaded, &g->shaded, &live);
  else
    m.shaded = {rs.width, rs.height, r.renderImage(current, current, RenderMode::Shaded, &live)};
  std::vector<float> levels = r.capturedLevels();
  // The instanced path decides its LOD on the CPU: the scheme's own counts of this pose are those of
  // the selection just drawn, taken before another pass selects again.
  // Instanced grid, GPU-indirect or mesh shaders: the drawn mesh, not patches, is checked for cracks.
  const bool instanced = r.path() != DrawPath::Tessellation;
  const std::vector<double> selectionCounts =
      r.path() == DrawPath::InstancedGrid ? r.lastSelection().counters : std::vector<double>{};
  lap("render");

  bool histogram = spec.on("histogram");
  if (histogram) try {
      m.histogram = r.measureHistogram(current, current, nullptr, spec.on("cracks"));  // the mesh: cracks only
    } catch (const FeatureMissing& e) {  // an optional pass: null with its reason, the frame stays
      m.unavailable["histogram"] = e.what();
      histogram = false;
      for (const char* k : {"tri_area_mean", "tri_area_median", "tri_frac_under_1px", "tri_frac_near_target"})
        set(k, kNan);
    }
  if (histogram) {
    m.hasHistogram = true;
    const TriangleHistogram& h = m.histogram;
    double target = scheme.targetAreaPx(params);
    HistogramStats hs = histogramStats(h, target > 0 ? target : kNan, h.areaSum);
    for (size_t i = 0; i < h.bins.size(); ++i) set("hist_" + std::to_string(i), double(h.bins[i]));
    set("hist_offscreen", double(h.offscreen));
    set("hist_backfacing", double(h.backfacing));
    set("hist_degenerate", double(h.degenerate));
    set("tri_area_mean", hs.meanArea);
    set("tri_area_median", hs.medianArea);
    set("tri_frac_under_1px", hs.fracUnder1px);
    set("tri_frac_near_target", hs.fracNearTarget);
    if (h.total() == h.offscreen + h.backfacing)
      m.unavailable["triangle_sizes"] = "no front-facing triangle on screen: tri_area_* and tri_frac_* are undefined";
  }
  lap("histogram");
  if (spec.on("error")) {
    GpuErrorStats s;
    if (g) {
      r.renderInto(current, current, RenderMode::Error, &g->error);
      s = g->reduce.errorStats(g->error);
      if (keepPixels) m.errorMap = g->readFloats(g->error);
    } else {
      m.errorMap = r.renderErrorMap(current, current);
      s = errorStats(m.errorMap);
    }
    if (s.count == 0)
      m.unavailable["error"] = "no terrain pixel on screen (every triangle clipped or culled): err_* undefined";
    set("err_mean_px", s.mean);
    set("err_p95_px", s.p95);
    set("err_max_px", s.max);
    lap("error");
    // Surplus: the error-bounded scheme's triangles at the bound whose measured p95 matches this
    // frame's (replay/surplus.h).
    if (spec.on("surplus") && s.count > 0) {
      SurplusResult sr = refs.surplus.match(ctx, terrain, rs, current, s.p95, live.stats.clipInvocations, g);
      set("surplus", sr.surplus);
      set("surplus_bound_px", sr.boundPx);
      set("surplus_p95_px", sr.boundP95);
      set("surplus_triangles", sr.boundTriangles);
      set("surplus_matched", double(sr.matched));
      lap("surplus");
    }
  }
  // Image metrics and crack pixels read the ray-cast ground truth (kImageReference), not `reference`.
  // Coverage rides on the truth the image or cracks pass needs (metrics/coverage.h).
  // The GPU path's comparison also counts coverage and crack candidates, so it runs for either pass.
  GpuImageStats gs;
  // A terrain past the GPU ray cast's limits has no truth on that path: the passes that compare
  // with it are null with the reason, the frame's other passes stand.
  std::string noTruth;
  if (g && (spec.on("image") || spec.on("cracks"))) try {
      g->castTruth(terrain, current);
    } catch (const FeatureMissing& e) {
      noTruth = e.what();
    }
  if (!noTruth.empty()) {
    lap("ray_cast");
    for (const char* pass : {"image", "cracks"})
      if (spec.on(pass)) m.unavailable[std::string(pass) == "cracks" ? "cracks_pixels" : pass] = noTruth;
    for (const char* k : {"coverage_missing_px", "coverage_extra_px", "coverage_truth_px"}) set(k, kNan);
    if (spec.on("image"))
      for (const char* k : {"img_psnr_db", "img_ssim", "img_mad", "img_frac_over", "flip_mean", "flip_p95"})
        set(k, kNan);
  } else if (spec.on("image") || spec.on("cracks")) {
    Coverage cov;
    if (g) {
      lap("ray_cast");
      gs = g->reduce.compare(g->shaded, g->truth, spec.diffThreshold, spec.on("image"));
      cov = {gs.coverageMissing, gs.coverageExtra, gs.truthTerrain};
      // Pixels only where a caller keeps them, or where crack candidates need the CPU's flood fill.
      if (keepPixels || (spec.on("cracks") && gs.crackCandidates > 0)) {
        m.shaded = g->readImage(g->shaded);
        m.reference = g->readImage(g->truth);
      }
    } else {
      m.reference = refs.image(ctx, terrain, terrainKey, rs, current);
      lap("ray_cast");
      cov = coverageError(m.shaded, m.reference);
    }
    set("coverage_missing_px", double(cov.missing));
    set("coverage_extra_px", double(cov.extra));
    set("coverage_truth_px", double(cov.truthTerrain));
  }
  if (spec.on("image") && noTruth.empty()) {
    ImageError ie = g ? gs.e : compareImages(m.shaded, m.reference, spec.diffThreshold);
    set("img_psnr_db", ie.psnrDb);
    set("img_ssim", ie.ssim);
    set("img_mad", ie.meanAbsDiff);
    set("img_frac_over", ie.fractionOver);
    lap("image");
    // FLIP of the frame against the truth as a viewer sees both, clear pixels as sky (metrics/flip.h);
    // on the GPU path its compute passes and a reduction of the map (metrics/gpu_flip.h).
    FlipStats fs;
    if (g) {
      const Buffer& map = g->flip(spec.flipPpd).run(g->truth, g->shaded);
      GpuErrorStats s = g->reduce.errorStats(map);
      fs = {s.mean, s.p95};
      if (keepPixels) m.flipMap = g->readFloats(map);
    } else {
      m.flipMap = flipMap(asSeen(m.reference), asSeen(m.shaded), spec.flipPpd);
      fs = flipStats(m.flipMap);
    }
    set("flip_mean", fs.mean);
    set("flip_p95", fs.p95);
    lap("flip");
  }
  // Crack pixels compare with the truth; analytic cracks read the geometry alone.
  const double crackPixels = noTruth.empty() && spec.on("cracks") ? double(cracks(m, g ? &gs : nullptr, rs)) : kNan;
  if (spec.on("cracks") && instanced) {
    // The drawn mesh, captured by the histogram pass (run for it here when the histogram is off).
    double analytic = kNan;
    try {
      if (!histogram) r.measureHistogram(current, current);
      const glm::vec2 lo(float(terrain.originX), float(terrain.originZ));
      analytic = double(meshCracks(r.capturedMesh(), {lo, lo + glm::vec2(terrain.extent)}).crackSites);
    } catch (const FeatureMissing& e) {
      m.unavailable["cracks_analytic"] = e.what();
    }
    set("cracks_analytic", analytic);
    set("cracks_pixels", crackPixels);
  } else if (spec.on("cracks")) {
    set("cracks_analytic", double(analyticCracks(scheme, params, terrain, rs.grid, levels)));
    set("cracks_pixels", crackPixels);
  }
  lap("cracks");
  if (spec.on("popping")) {
    // A case's first frame has no previous frame: popping is undefined there (null), not 0, so
    // summaries average only frames that could pop.
    // Lag k = 1 .. kPopLags: a stateful LOD's state of frame t - k drawn from this view against this
    // frame, or the LOD camera of frame t - k, all of those drawn beside one live frame.
    std::vector<const RgbaImage*> images(kPopLags, nullptr);
    std::vector<CameraPose> poses;
    std::vector<int> poseLag;
    for (int k = 1; k <= kPopLags && frame >= k; ++k) {
      const size_t i = size_t(k - 2);
      if (k == 1 && popBefore)
        images[0] = popBefore;
      else if (k > 1 && older && i < older->images.size())
        images[size_t(k - 1)] = &older->images[i];
      else if (k == 1 || (older && i < older->poses.size()))
        poses.push_back(k == 1 ? previous : older->poses[i]), poseLag.push_back(k);
    }
    std::vector<PopResult> fromPoses = poses.empty() ? std::vector<PopResult>{} : measurePopping(r, poses, current, g);
    for (int k = 1; k <= kPopLags; ++k) {
      if (k > 1 && !older) break;  // lags beyond 1 only where the caller gave the older LOD
      PopResult p{kNan, kNan, 0};
      bool have = false;
      if (const RgbaImage* img = images[size_t(k - 1)]) {
        ImageError e =
            g ? g->reduce.compare(g->reduce.upload(*img), g->shaded, 16, false).e : compareImages(*img, m.shaded);
        p = {e.meanAbsDiff, e.p99AbsDiff, e.changedPixels}, have = true;
      }
      for (size_t j = 0; j < poseLag.size(); ++j)
        if (poseLag[j] == k) p = fromPoses[j], have = true;
      const std::string key = k == 1 ? "pop" : "pop" + std::to_string(k);
      set(key + "_mean", p.mean);
      set(key + "_p99", p.p99);
      set(key + "_changed", have ? double(p.changed) : kNan);
    }
    lap("popping");
  }
  // Saturation is a tessellation level at its cap, where levels are decided per patch (the
  // tessellation path, a mesh path's patches); the other paths' schemes count their own limits
  // (SchemeInfo::counters).
  const bool patchLevels = r.patchCount() > 0;
  if (!patchLevels)
    m.unavailable["saturated_patches"] =
        "no tessellation levels on this draw path: the scheme's own counters say where it hits its limits";
  set("saturated_patches", patchLevels ? saturatedPatches(levels, scheme.partitioning(params)) : kNan);
  const std::vector<SchemeCounter>& counters = scheme.info().counters;
  if (!counters.empty()) {
    std::vector<double> counts = r.path() == DrawPath::InstancedGrid ? selectionCounts : scheme.countFrame(levels);
    for (size_t i = 0; i < counters.size(); ++i) set(counters[i].frameKey, i < counts.size() ? counts[i] : kNan);
  }
  return m;
}

RgbaImage errorImage(const std::vector<float>& error, int width, int height) {
  RgbaImage img{width, height, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 255)};
  for (size_t i = 0; i < error.size(); ++i) {
    uint8_t* p = &img.px[i * 4];
    if (error[i] < 0) {  // no terrain: the sky of images for people
      p[0] = kSkyRgba[0], p[1] = kSkyRgba[1], p[2] = kSkyRgba[2];
      continue;
    }
    // sqrt scale so sub-pixel errors stay visible: 0 px black, 8 px and more white.
    auto v = uint8_t(std::lround(255.0 * std::min(1.0, std::sqrt(double(error[i]) / 8.0))));
    p[0] = p[1] = p[2] = v;
  }
  return img;
}

}  // namespace lb
