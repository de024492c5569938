#include "replay/matched.h"

#include <cmath>
#include <memory>

#include "camera/camera_path.h"
#include "config/config.h"
#include "render/renderer.h"
#include "replay/lod_replay.h"
#include "replay/measure_gpu.h"
#include "stats.h"

namespace lb {

MatchResult matchParameter(Context& ctx, const Scheme& scheme, const ParamValues& base, const Heightfield& terrain,
                           const CameraPath& path, const Config& config, const Case& c) {
  const MatchSpec& spec = config.match;
  MatchResult out;
  out.param = scheme.info().mainParam;
  if (out.param.empty()) return out;
  const ParamSpec* ps = nullptr;
  for (auto& p : scheme.info().params)
    if (p.name == out.param) ps = &p;
  int frames = frameCount(path, config.fps);
  if (config.maxFrames > 0) frames = std::min(frames, config.maxFrames);
  Renderer r(ctx, terrain, {c.width, c.height, c.grid});
  // On the GPU path (replay/measure_gpu.h) each trial's error map is reduced on the device.
  std::unique_ptr<GpuReduce> reduce;
  Buffer errorMap;
  if (spec.metric != "triangles" && measureOnGpu(config.measure, ctx)) {
    reduce = std::make_unique<GpuReduce>(ctx, c.width, c.height);
    errorMap = createBuffer(ctx, VkDeviceSize(c.width) * VkDeviceSize(c.height) * 4,
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
  }

  auto poseAt = [&](int f) { return samplePose(path, config.fps, f, terrain); };
  auto evaluate = [&](double v) {
    ParamValues pv = base;
    pv[out.param] = ps->integer ? std::round(v) : v;
    r.setScheme(scheme, pv);
    // A stateful LOD is judged on the states its case would draw: converged, warmed up, then the
    // path's updates up to each evaluated frame (replay/lod_replay.h), drawn frozen there.
    std::unique_ptr<LodReplay> replay;
    if (r.statefulLod()) {
      startLod(r, poseAt(0), config.warmupFrames);
      replay = std::make_unique<LodReplay>(r, poseAt, std::vector<uint32_t>{});
    }
    double sum = 0;
    int n = std::max(1, std::min(spec.frames, frames));
    for (int k = 0; k < n; ++k) {
      int f = n == 1 ? 0 : k * (frames - 1) / (n - 1);
      CameraPose p = poseAt(f);
      std::unique_ptr<FrozenLod> frozen;
      if (replay) {
        replay->advanceTo(f);
        frozen = std::make_unique<FrozenLod>(r);
      }
      if (spec.metric == "triangles") {
        r.submitFrame(f, p, p);
        r.finish();
        sum += double(r.takeCompleted().back().stats.clipInvocations);
      } else if (reduce) {
        r.renderInto(p, p, RenderMode::Error, &errorMap);
        GpuErrorStats es = reduce->errorStats(errorMap);
        sum += es.count == 0 ? 0 : spec.metric == "err_p95_px" ? es.p95 : es.mean;
      } else if (spec.metric == "err_p95_px") {
        std::vector<double> e;
        for (float v : r.renderErrorMap(p, p))
          if (v >= 0) e.push_back(v);
        sum += e.empty() ? 0 : summarize(e).p95;
      } else {
        auto err = r.renderErrorMap(p, p);
        double s = 0;
        int m = 0;
        for (float e : err)
          if (e >= 0) s += e, ++m;
        sum += m ? s / m : 0;
      }
    }
    ++out.evaluations;
    return sum / n;
  };
  // Parameters spanning orders of magnitude (a triangle width of 0.5..64 px) are searched in log space.
  bool logScale = ps->min > 0 && ps->max / ps->min > 16;
  auto toX = [&](double v) { return logScale ? std::log(v) : v; };
  auto fromX = [&](double x) { return logScale ? std::exp(x) : x; };
  double lo = toX(ps->min), hi = toX(ps->max);
  double flo = evaluate(fromX(lo)), fhi = evaluate(fromX(hi));
  bool increasing = fhi >= flo;
  double target = spec.value;
  if ((increasing && (target < flo || target > fhi)) || (!increasing && (target > flo || target < fhi))) {
    out.reachable = false;
    bool takeLo = std::abs(target - flo) < std::abs(target - fhi);
    out.value = fromX(takeLo ? lo : hi);
    out.achieved = takeLo ? flo : fhi;
  } else {
    for (int i = 0; i < spec.iterations; ++i) {
      double mid = 0.5 * (lo + hi);
      if (ps->integer && std::round(fromX(hi)) - std::round(fromX(lo)) <= 1) break;
      double fm = evaluate(fromX(mid));
      if ((fm < target) == increasing)
        lo = mid, flo = fm;
      else
        hi = mid, fhi = fm;
    }
    bool takeLo = std::abs(target - flo) <= std::abs(target - fhi);
    out.value = fromX(takeLo ? lo : hi);
    out.achieved = takeLo ? flo : fhi;
  }
  if (ps->integer) out.value = std::round(out.value);
  return out;
}

}  // namespace lb
