#pragma once
// How long a scheme's LOD lags the camera (docs/results-format.md, "settle"): for every frame of the
// path, the frame's mean screen-space error (err_mean_px) against its settled value, the error of the
// LOD the scheme reaches at that camera given time. A LOD decided from the current camera alone is
// settled on every frame by construction; a stateful one (a tree refined a few levels per update,
// replay/lod_replay.h) is settled at a frame's camera by updating there until its instance count
// holds, then put back. The lag after a camera jump is the longest run of frames whose error is off
// its settled value by more than kSettleTolerance of it.
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "camera/camera_path.h"

namespace lb {

class Renderer;

constexpr double kSettleTolerance = 0.10;

struct SettleFrame {
  int frame = 0;
  double err = 0;      // err_mean_px of the frame's LOD; NaN where no terrain pixel is drawn
  double settled = 0;  // err_mean_px of the LOD settled at the frame's camera; NaN where unknown
};

// A frame is off when |err - settled| > tolerance x settled; a frame with an unknown value ends a run
// and is not counted. {"frames": the longest run's length (0: none), "from", "to" (its first and last
// frame, null without a run), "off_frames": every frame off, "frames_compared", "tolerance",
// "settled_by", "counted": [{frame, err_mean_px, settled_err_mean_px}] of the longest run and the
// frame after it (the one back within the tolerance, where the path has it)}.
nlohmann::json settleJson(const std::vector<SettleFrame>& series, const char* settledBy,
                          double tolerance = kSettleTolerance);

// A LOD of the current camera alone: settled on every frame, no run, nothing to render.
nlohmann::json settledByCamera(int frames);

// The stateful renderer's frames 0 .. frames - 1 replayed from its snapshot (LodReplay, checked
// against the timed instance counts), each drawn frozen as an error map, then settled and drawn
// again; the state is put back before the next frame's update.
std::vector<SettleFrame> settleSeries(Renderer& r, const std::function<CameraPose(int)>& pose, int frames,
                                      const std::vector<uint32_t>& timedInstances);

}  // namespace lb
