#include "replay/settle.h"

#include <cmath>

#include "render/lod_state.h"
#include "render/renderer.h"
#include "replay/lod_replay.h"

namespace lb {

using nlohmann::json;

static json number(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

json settleJson(const std::vector<SettleFrame>& series, const char* settledBy, double tolerance) {
  auto off = [&](const SettleFrame& f) { return std::abs(f.err - f.settled) > tolerance * f.settled; };
  auto known = [](const SettleFrame& f) { return std::isfinite(f.err) && std::isfinite(f.settled); };
  size_t bestFrom = 0, bestLen = 0, offFrames = 0, compared = 0;
  for (size_t i = 0; i < series.size();) {
    if (!known(series[i]) || !off(series[i])) {
      compared += known(series[i]);
      ++i;
      continue;
    }
    size_t j = i;
    while (j < series.size() && known(series[j]) && off(series[j])) ++j;
    offFrames += j - i;
    compared += j - i;
    if (j - i > bestLen) bestFrom = i, bestLen = j - i;
    i = j;
  }
  json counted = json::array();
  for (size_t i = bestFrom; bestLen > 0 && i < series.size() && i <= bestFrom + bestLen; ++i)
    counted.push_back({{"frame", series[i].frame},
                       {"err_mean_px", number(series[i].err)},
                       {"settled_err_mean_px", number(series[i].settled)}});
  return {{"frames", bestLen},
          {"from", bestLen ? json(series[bestFrom].frame) : json(nullptr)},
          {"to", bestLen ? json(series[bestFrom + bestLen - 1].frame) : json(nullptr)},
          {"off_frames", offFrames},
          {"frames_compared", compared},
          {"tolerance", tolerance},
          {"settled_by", settledBy},
          {"counted", counted}};
}

json settledByCamera(int frames) {
  return {{"frames", 0},
          {"from", nullptr},
          {"to", nullptr},
          {"off_frames", 0},
          {"frames_compared", frames},
          {"tolerance", kSettleTolerance},
          {"settled_by", "camera"},
          {"counted", json::array()}};
}

// err_mean_px of one error map (negative: no terrain); NaN without terrain.
static double meanError(const std::vector<float>& map) {
  double s = 0;
  long n = 0;
  for (float v : map)
    if (v >= 0) s += v, ++n;
  return n ? s / double(n) : std::nan("");
}

std::vector<SettleFrame> settleSeries(Renderer& r, const std::function<CameraPose(int)>& pose, int frames,
                                      const std::vector<uint32_t>& timedInstances) {
  LodState& lod = r.lodState();
  LodReplay replay(r, pose, timedInstances);
  std::vector<SettleFrame> out;
  for (int f = 0; f < frames; ++f) {
    replay.advanceTo(f);
    const CameraPose p = pose(f);
    SettleFrame s{f, std::nan(""), std::nan("")};
    {
      FrozenLod frozen(r);
      s.err = meanError(r.renderErrorMap(p, p));
    }
    // Settled as convergeLod settles, but from the frame's state rather than a reset.
    lod.keep();
    const int limit = int(lod.gpuLod().convergeLimit);
    uint32_t last = 0;
    for (int u = 0, steady = 0; u < limit && steady < kSteadyUpdates; ++u) {
      uint32_t n = lod.update(p);
      steady = u > 0 && n == last ? steady + 1 : 0;
      last = n;
    }
    if (lod.overflow() == 0) {  // a settled state past the pool would be missing leaves: unknown
      FrozenLod frozen(r);
      s.settled = meanError(r.renderErrorMap(p, p));
    }
    lod.putBack();
    out.push_back(s);
  }
  return out;
}

}  // namespace lb
