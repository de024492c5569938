#pragma once
// The timing side of a case beyond the shaded frames: replays of the path in the
// depth and frontend timing modes, checked against the shaded frames' counters, and the
// clock-control calibration run before and after the timed frames.
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera/camera_path.h"
#include "config/timing_spec.h"
#include "render/renderer.h"

namespace lb {

struct Context;
struct Heightfield;
struct CameraPose;

RenderMode timingRenderMode(const std::string& name);  // shaded | depth | frontend

// Replays `frames` frames x `repetitions` in `mode` (after `warmup` unrecorded frames of frame 0)
// and returns the results in submission order, like the shaded loop's.
std::vector<FrameResult> replayInMode(Renderer& renderer, RenderMode mode, int frames, int repetitions, int warmup,
                                      const std::function<CameraPose(int)>& pose);

// Empty when the tessellation counters (input assembly, vertex, control, evaluation) of `other`
// equal `shaded` frame by frame; else a message naming the first frame and counter that differ.
std::string compareTessellationCounters(const std::vector<FrameResult>& shaded, const std::vector<FrameResult>& other,
                                        const std::string& mode);

struct CalibrationRun {
  std::vector<double> runsMs;  // each run's median frame time, in order
  bool stable = false;         // the last 3 runs lie within the tolerance
  double loadS = 0;            // seconds of sustained calibration load before the first counted run
  double ms() const { return runsMs.empty() ? 0 : runsMs.back(); }
};
// True when the last 3 values lie within `tolerance` ((max - min) / median).
bool calibrationStable(const std::vector<double>& runsMs, double tolerance);
// The calibration workload: uniform at spec.level on the case's grid and resolution, from the
// case's first pose. Built once per case so the run after the timed frames needs no pipeline
// compile (CPU time during which the GPU would idle and its clock drop).
class Calibrator {
 public:
  Calibrator(Context& ctx, const Heightfield& terrain, const RenderSettings& settings, const TimingSpec& spec,
             const CameraPose& pose);
  double runOnce();              // median GPU ms over spec.frames frames
  CalibrationRun untilStable();  // runs until calibrationStable() or spec.maxTries runs

 private:
  Renderer renderer_;
  TimingSpec spec_;
  CameraPose pose_;
};
// {"before_ms", "after_ms", "before_runs", "stable_before", "drift", "flagged"}: after is one run
// right after the timed frames; flagged when |after / before - 1| > spec.driftLimit or unknown.
nlohmann::json calibrationJson(const CalibrationRun& before, double afterMs, const TimingSpec& spec);

// A CPU rasterizer (lavapipe) has no GPU clock to control. Tests pretend a GPU with
// LODBENCH_TEST_DEVICE_TYPE=gpu, so the default and the flag below are testable on lavapipe.
bool cpuRasterizer(const Context& ctx);
// Whether a case calibrates: the config's choice where it made one, else on for every device that
// is not a CPU rasterizer.
bool calibrationWanted(const TimingSpec& spec, const Context& ctx);
// The calibration record of a case that did not calibrate: {"controlled": false, "reason", "flagged"},
// flagged on a GPU ("clock not controlled": its timings may come from any clock), not on a CPU
// rasterizer.
nlohmann::json uncalibratedJson(const TimingSpec& spec, const Context& ctx);

}  // namespace lb
