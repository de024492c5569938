// Energy per frame over windows of whole counter ticks (replay/energy_pass.h).
#include "replay/energy_pass.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "camera/camera_path.h"
#include "render/lod_state.h"
#include "render/renderer.h"
#include "vk/energy_counter.h"

namespace lb {

using nlohmann::json;

namespace {

constexpr double kPollS = 0.0005;     // the counter is read at most this often (NVML calls cost host time)
constexpr double kTickWaitS = 5.0;    // a counter that does not change in this long is stuck
constexpr double kSecondsToMs = 1e3;  // seconds -> ms

double median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

EnergyResult measureEnergy(EnergyCounter& counter, double windowS, int rounds, const std::function<int64_t()>& draw) {
  EnergyResult out;
  out.windowS = windowS;
  out.counter = counter.name();
  if (!counter.available()) {
    out.reason = counter.reason();
    return out;
  }
  std::optional<uint64_t> first = counter.readMj();
  if (!first) {
    out.reason = counter.readError();
    return out;
  }
  uint64_t last = *first;
  int64_t completed = 0;
  double lastPoll = -INFINITY;
  // Draws until the counter changes and returns the time it was seen changed; nullopt when it did
  // not by `deadline` (the counter's clock) or a read failed (out.reason says which).
  auto untilTick = [&](double deadline) -> std::optional<double> {
    for (;;) {
      completed = draw();
      const double t = counter.now();
      if (t - lastPoll < kPollS) continue;
      lastPoll = t;
      std::optional<uint64_t> v = counter.readMj();
      if (!v) {
        out.reason = counter.readError();
        return std::nullopt;
      }
      if (*v < last) {
        out.reason =
            "the energy counter went backwards (" + std::to_string(last) + " mJ, then " + std::to_string(*v) + " mJ)";
        return std::nullopt;
      }
      if (*v != last) {
        last = *v;
        return t;
      }
      if (t > deadline) {
        out.reason = "the energy counter (" + counter.name() + ") did not change in " +
                     std::to_string(int(kTickWaitS)) + " s of drawing";
        return std::nullopt;
      }
    }
  };
  // Back-to-back windows: the tick that closes one opens the next.
  std::optional<double> open = untilTick(counter.now() + kTickWaitS);
  if (!open) return out;
  for (int r = 0; r < rounds; ++r) {
    const double t0 = *open;
    const int64_t c0 = completed;
    const uint64_t e0 = last;
    std::vector<double> ticks;  // times between the changes seen in this window
    double prev = t0;
    for (;;) {
      std::optional<double> t = untilTick(t0 + windowS + kTickWaitS);
      if (!t) return out;
      ticks.push_back(*t - prev);
      prev = *t;
      if (*t - t0 < windowS) continue;
      EnergyRound round;
      round.joules = double(last - e0) / 1000.0;
      round.frames = completed - c0;
      round.seconds = *t - t0;
      round.tickMs = ticks.size() >= 2 ? kSecondsToMs * median(ticks) : -1;
      round.smClockMhz = counter.clocks().smMhz;
      out.rounds.push_back(round);
      open = t;
      break;
    }
    if (out.rounds.back().frames <= 0) {
      out.reason = "no frame completed in an energy window";
      return out;
    }
  }
  return out;
}

EnergyResult energyPass(Renderer& renderer, EnergyCounter& counter, const TimingSpec& spec, int frames,
                        const std::function<CameraPose(int)>& pose, const std::function<void()>& check) {
  EnergyResult none;
  none.windowS = spec.energyWindowS;
  none.counter = counter.name();
  none.pathFrames = frames;
  if (!spec.energy) {
    none.reason = "\"energy\": false in the config";
    return none;
  }
  if (!counter.available()) {
    none.reason = counter.reason();
    return none;
  }
  if (frames <= 0) {
    none.reason = "the path has no frames";
    return none;
  }
  std::vector<CameraPose> poses;
  for (int f = 0; f < frames; ++f) poses.push_back(pose(f));
  renderer.finish();
  renderer.takeCompleted();
  int next = 0;
  int64_t completed = 0;
  auto draw = [&]() -> int64_t {
    check();
    if (next == frames) next = 0;
    if (next == 0 && renderer.statefulLod()) renderer.lodState().restore();  // S0, as the timed passes
    renderer.submitFrame(next, poses[size_t(next)], poses[size_t(next)]);
    ++next;
    completed += int64_t(renderer.takeCompleted().size());
    return completed;
  };
  EnergyResult r = measureEnergy(counter, spec.energyWindowS, spec.energyRounds, draw);
  renderer.finish();
  renderer.takeCompleted();
  r.pathFrames = frames;
  return r;
}

json energyJson(const EnergyResult& r) {
  if (!r.measured())
    return {{"energy_j_per_frame", nullptr}, {"energy_reason", r.reason.empty() ? "not measured" : r.reason}};
  std::vector<double> jpf, joules, seconds, passes, ticks;
  std::vector<int64_t> frames;
  json clocks = json::array();
  for (const EnergyRound& k : r.rounds) {
    jpf.push_back(k.jPerFrame());
    joules.push_back(k.joules);
    frames.push_back(k.frames);
    seconds.push_back(k.seconds);
    if (r.pathFrames > 0) passes.push_back(double(k.frames) / double(r.pathFrames));
    if (k.tickMs > 0) ticks.push_back(k.tickMs);
    clocks.push_back(k.smClockMhz >= 0 ? json(k.smClockMhz) : json(nullptr));
  }
  double mean = 0;
  for (double v : jpf) mean += v / double(jpf.size());
  const double lo = *std::min_element(jpf.begin(), jpf.end()), hi = *std::max_element(jpf.begin(), jpf.end());
  json e = {{"mean", mean},
            {"min", lo},
            {"max", hi},
            {"spread", mean > 0 ? json((hi - lo) / mean) : json(nullptr)},
            {"rounds", jpf},
            {"round_joules", joules},
            {"round_frames", frames},
            {"round_seconds", seconds},
            {"path_passes", passes},
            {"window_s", r.windowS},
            {"tick_ms", ticks.empty() ? json(nullptr) : json(median(ticks))},
            {"sm_clock_mhz", clocks},
            {"counter", r.counter}};
  return {{"energy_j_per_frame", e}, {"energy_reason", nullptr}};
}

}  // namespace lb
