#pragma once
// Energy per frame from the board's energy counter (vk/energy_counter.h), after a case's timed
// frames: `rounds` windows, each from one tick of the counter to the first tick at least `window_s`
// later, with the path's frames drawn (the path looped) all the while; J/frame = the counter's
// difference / the frames the GPU completed in the window. The counter's own sampling (the H100's
// sensor is said to see a quarter of each window) makes rounds differ: their spread is recorded,
// and the report ranks two schemes on energy only where their rounds do not overlap.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/timing_spec.h"

namespace lb {

class EnergyCounter;
class Renderer;
struct CameraPose;

struct EnergyRound {
  double joules = 0;    // the counter's difference over the window
  int64_t frames = 0;   // frames the GPU completed in the window
  double seconds = 0;   // from the tick that opened the window to the one that closed it (>= window_s)
  double tickMs = -1;   // median time between the counter's changes seen in the window; < 0: fewer than 2
  int smClockMhz = -1;  // the SM clock at the window's end (NVML); < 0: unknown
  double jPerFrame() const { return frames > 0 ? joules / double(frames) : -1; }
};

struct EnergyResult {
  std::string reason;  // "" when measured; else why there is no figure
  std::vector<EnergyRound> rounds;
  double windowS = 0;   // the window asked for
  int pathFrames = 0;   // frames of one pass over the path (0: not a path)
  std::string counter;  // the counter's name
  bool measured() const { return reason.empty() && !rounds.empty(); }
};

// The windows over any load: draw() draws one more frame and returns the frames the GPU has
// completed since the pass began. Polls the counter after each frame (at most every 0.5 ms of the
// counter's clock). A counter that does not tick within 5 s (plus the window) gives a reason, not
// a figure.
EnergyResult measureEnergy(EnergyCounter& counter, double windowS, int rounds, const std::function<int64_t()>& draw);

// The pass over a case's renderer: frames 0 .. frames-1 of the path, again and again; a stateful
// scheme restores its snapshot at the start of every pass over the path, as the timed passes do.
// check() is called between frames (throws to stop).
EnergyResult energyPass(Renderer& renderer, EnergyCounter& counter, const TimingSpec& spec, int frames,
                        const std::function<CameraPose(int)>& pose, const std::function<void()>& check);

// The case summary's fields: {"energy_j_per_frame": {mean, min, max, spread, rounds, ...} or null,
// "energy_reason": null or why}. Never 0 for unknown.
nlohmann::json energyJson(const EnergyResult& r);

}  // namespace lb
