#include "replay/surplus.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "camera/camera_path.h"
#include "replay/measure_gpu.h"
#include "schemes/registry.h"
#include "stats.h"
#include "terrain/heightfield.h"

namespace lb {

static const double kNan = std::nan("");
constexpr double kTolerance = 0.02;
constexpr int kMaxRenders = 14;

double errorP95(const std::vector<float>& errorMap) {
  std::vector<double> e;
  for (float v : errorMap)
    if (v >= 0) e.push_back(v);
  return e.empty() ? kNan : summarize(e).p95;
}

SurplusResult SurplusMatcher::match(Context& ctx, const Heightfield& terrain, const RenderSettings& settings,
                                    const CameraPose& pose, double target, uint64_t schemeTriangles, MeasureGpu* gpu) {
  const Scheme* bounded = schemeWithRole(MainParamRole::ErrorBoundPx);
  if (!bounded) throw std::logic_error("surplus: no registered scheme has an error-bound main parameter");
  const SchemeInfo& info = bounded->info();
  const ParamSpec* boundSpec = nullptr;
  for (const ParamSpec& p : info.params)
    if (p.name == info.mainParam) boundSpec = &p;
  const double minBound = boundSpec->min, maxBound = boundSpec->max;
  if (!renderer_ || terrain_ != &terrain || settings_.width != settings.width || settings_.height != settings.height ||
      settings_.grid != settings.grid) {
    renderer_.reset();
    renderer_ =
        std::make_unique<Renderer>(ctx, terrain, RenderSettings{settings.width, settings.height, settings.grid});
    renderer_->setScheme(*bounded, {});
    terrain_ = &terrain;
    settings_ = settings;
  }
  SurplusResult out;
  out.surplus = out.boundPx = out.boundP95 = out.boundTriangles = kNan;
  struct Sample {
    double bound = 0, p95 = 0, triangles = 0;
  };
  auto eval = [&](double bound) {
    renderer_->setUniformParams({{info.mainParam, bound}});
    FrameResult fr;
    ++out.renders;
    if (gpu) {
      renderer_->renderInto(pose, pose, RenderMode::Error, &gpu->surplusError, &fr);
      return Sample{bound, gpu->reduce.errorStats(gpu->surplusError).p95, double(fr.stats.clipInvocations)};
    }
    std::vector<uint8_t> bytes = renderer_->renderImage(pose, pose, RenderMode::Error, &fr);
    std::vector<float> px(bytes.size() / sizeof(float));
    std::memcpy(px.data(), bytes.data(), px.size() * sizeof(float));
    return Sample{bound, errorP95(px), double(fr.stats.clipInvocations)};
  };
  auto within = [&](const Sample& s) { return std::abs(s.p95 - target) <= kTolerance * target; };
  auto take = [&](const Sample& s, int matched) {
    out.boundPx = s.bound;
    out.boundP95 = s.p95;
    out.boundTriangles = s.triangles;
    out.matched = matched;
    if (s.triangles > 0) out.surplus = double(schemeTriangles) / s.triangles;
  };
  if (!std::isfinite(target)) return out;
  // The p95 grows with the bound (more error allowed, coarser levels), roughly in proportion: search
  // log(bound) by regula falsi (Illinois) between the closest bounds under and over the target, with
  // a proportional step while only one side is known and bisection when a step would not shrink the
  // bracket; the same 2% acceptance as a plain bisection (on the default job's sphere and cdlod cases
  // 6.8 renders a frame against bisection's 9.5).
  const double lo0 = std::log(minBound), hi0 = std::log(maxBound);
  double lo = lo0, hi = hi0;
  bool haveBelow = false, haveAbove = false;
  Sample below, above;            // closest bounds with p95 under / over the target
  double fBelow = 0, fAbove = 0;  // the bracket ends' misses (p95 - target) the secant uses
  int sameSide = 0;               // samples in a row on one side of the target
  int lastSide = 0;
  double next = std::log(std::clamp(2.0 * target, minBound, maxBound));
  while (out.renders < kMaxRenders) {
    const double x = next;
    Sample s = eval(std::exp(x));
    if (within(s)) {
      take(s, 1);
      return out;
    }
    const int side = s.p95 < target ? -1 : 1;
    if (side < 0) {
      lo = x, below = s, haveBelow = true, fBelow = s.p95 - target;
      if (x >= hi0 - 1e-9) break;  // even the loosest bound is more accurate
    } else {
      hi = x, above = s, haveAbove = true, fAbove = s.p95 - target;
      if (x <= lo0 + 1e-9) break;  // even the tightest bound is less accurate
    }
    sameSide = side == lastSide ? sameSide + 1 : 0;
    lastSide = side;
    if (hi - lo < 1e-2) break;  // bracket closed to 1% of the bound: p95 jumps over the target here
    if (!haveBelow || !haveAbove) {
      // One side known: step in proportion to the miss (p95 ~ bound), to the range's end at most.
      double step = s.p95 > 0 ? std::log(target / s.p95) : hi0 - lo0;
      step = side < 0 ? std::max(step, 0.05) : std::min(step, -0.05);
      next = std::clamp(x + step * (1 << std::min(sameSide, 4)), lo0, hi0);
      continue;
    }
    // Both sides known: the secant through the bracket's ends, the kept end's miss halved when the
    // same end moves twice in a row (Illinois), inside the bracket's middle 90% or else bisected.
    if (sameSide >= 1) (side < 0 ? fAbove : fBelow) *= 0.5;
    double t = fAbove != fBelow ? lo + (hi - lo) * (-fBelow) / (fAbove - fBelow) : 0.5 * (lo + hi);
    next = t > lo + 0.05 * (hi - lo) && t < hi - 0.05 * (hi - lo) ? t : 0.5 * (lo + hi);
  }
  if (haveBelow && haveAbove && above.p95 > below.p95) {
    double f = (target - below.p95) / (above.p95 - below.p95);
    Sample mix{std::exp(std::log(below.bound) + f * (std::log(above.bound) - std::log(below.bound))), target,
               below.triangles + f * (above.triangles - below.triangles)};
    take(mix, 0);
    out.boundP95 = std::abs(below.p95 - target) < std::abs(above.p95 - target) ? below.p95 : above.p95;
  }
  return out;
}

}  // namespace lb
