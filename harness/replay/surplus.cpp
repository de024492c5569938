#include "replay/surplus.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "camera/camera_path.h"
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
                                    const CameraPose& pose, double target, uint64_t schemeTriangles) {
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
    std::vector<uint8_t> bytes = renderer_->renderImage(pose, pose, RenderMode::Error, &fr);
    std::vector<float> px(bytes.size() / sizeof(float));
    std::memcpy(px.data(), bytes.data(), px.size() * sizeof(float));
    ++out.renders;
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
  // The p95 grows with the bound (more error allowed, coarser levels); bisect log(bound).
  double lo = std::log(minBound), hi = std::log(maxBound);
  bool haveBelow = false, haveAbove = false;
  Sample below, above;  // closest bounds with p95 under / over the target
  double next = std::log(std::clamp(2.0 * target, minBound, maxBound));
  while (out.renders < kMaxRenders) {
    Sample s = eval(std::exp(next));
    if (within(s)) {
      take(s, 1);
      return out;
    }
    if (s.p95 < target) {
      lo = next, below = s, haveBelow = true;
      if (next >= std::log(maxBound) - 1e-9) break;  // even the loosest bound is more accurate
    } else {
      hi = next, above = s, haveAbove = true;
      if (next <= std::log(minBound) + 1e-9) break;  // even the tightest bound is less accurate
    }
    if (hi - lo < 1e-3) break;  // bracket closed: p95 jumps over the target here
    // Extremes first so a target outside the bound's reach is recognised in one render.
    next = !haveAbove ? std::log(maxBound) : !haveBelow ? std::log(minBound) : 0.5 * (lo + hi);
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
