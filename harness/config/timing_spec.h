#pragma once
// Config of the timing side of a case: which timing modes replay the path, the clock-control
// calibration run before and after the timed frames, and the energy windows after them.
#include <string>
#include <vector>

namespace lb {

struct TimingSpec {
  // "shaded" (always timed: the case's gpu_ms), "depth", "frontend" (see RenderMode).
  std::vector<std::string> modes{"shaded"};
  // Calibration: uniform `level` on the case's grid and resolution, `frames` frames per run (their
  // median is the run's time), repeated until 3 consecutive runs lie within `tolerance` of each
  // other or `maxTries` runs were made; again after the timed frames. `calibrate` holds the config's
  // choice where `calibrateSet`; unset, it is on for every device that is not a CPU rasterizer
  // (replay/timing_passes.h calibrationWanted): a real GPU's timings are wrong at an idle clock.
  bool calibrate = false;
  bool calibrateSet = false;
  int level = 16, frames = 5, maxTries = 12;
  double tolerance = 0.01;   // stable: (max - min) / median of the last 3 runs
  double driftLimit = 0.02;  // flagged: |after / before - 1| above this
  // Sustained load before the stability check: a GPU at its idle clock is "stable" too (H100: three
  // runs at 11.74 ms within 0.01%, then 2.91 ms after the case), and its governor raises the clock
  // only after a few hundred ms of continuous work.
  double minLoadS = 1.0;
  double testDrift = 0;  // tests only (never from JSON): the after-run's time x (1 + testDrift)
  // Energy per frame (replay/energy_pass.h), where the device has an energy counter (NVML): after
  // the timed frames, `energyRounds` windows, each from one tick of the counter to the first tick at
  // least `energyWindowS` seconds later, the path looped while they last. Config "energy": false,
  // or {"window_s", "rounds"}.
  bool energy = true;
  double energyWindowS = 2.0;
  int energyRounds = 3;
};

}  // namespace lb
