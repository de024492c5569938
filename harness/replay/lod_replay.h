#pragma once
// Stateful LOD schemes (Renderer::statefulLod: a tree the GPU refines a little every frame) are
// measured on the state the timed frames drew. The timed frame f drew S0 updated with the poses of
// frames 0 ... f, S0 being the converged state after the warm-up (snapshotted, restored before every
// repetition and timing-mode replay). Measurement, images and matched searches replay those updates
// alone and draw frozen (LodState::setFrozen) at the frames they look at; a replay whose instance
// counts differ from the timed frames' fails the case ("LOD replay diverged"). Everything here
// goes through the renderer's LOD state (render/lod_state.h).
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera/camera_path.h"
#include "render/frame_data.h"
#include "render/lod_state.h"
#include "render/renderer.h"

namespace lb {

struct ConvergeResult {
  int updates = 0;         // updates run from the reset
  bool converged = false;  // the instance count held for kSteadyUpdates updates within the limit
  uint32_t instances = 0;  // at the end
  // SHA-256 of the converged tree: the state words the scheme names as its tree (GpuLod::treeFirstWord,
  // cbt's leaf bitfield), not the header, so equal hashes mean the same leaves on any device,
  // terrain height range or update count.
  std::string stateSha256;
};
constexpr int kSteadyUpdates = 4;

// Resets the state, then updates at `pose` until the instance count is unchanged for kSteadyUpdates
// updates, at most GpuLod::convergeLimit; not converging is recorded, not fatal.
ConvergeResult convergeLod(Renderer& r, const CameraPose& pose);

// S0 as a case's timed frames start from it: converged at the path's first pose, then `warmup`
// updates there (the warm-up frames'), snapshotted. For the callers that rebuild a case's states
// outside its sweep (matched searches, `lodbench render`): they record no convergence, so the state
// is neither read back nor hashed (16 MiB and a SHA-256 of 4 MiB for cbt at depth 25, every trial).
void startLod(Renderer& r, const CameraPose& first, int warmup);

// The case's state record: converge_updates, lod_converged and the scheme's facts (GpuLod::facts).
nlohmann::json lodStateJson(const ConvergeResult& c, const std::vector<std::pair<std::string, double>>& facts);

// Checks that every repetition's instance counts equal the first's (each started from S0) and
// returns the first repetition's, frame by frame; throws "LOD replay diverged" otherwise.
std::vector<uint32_t> timedInstances(const std::vector<FrameResult>& frames, int framesPerRep);

// Walks a renderer's state along the path from S0 (its snapshot): advanceTo(f) runs the updates of
// the frames not yet replayed, up to f, checking each count against the timed frames'.
class LodReplay {
 public:
  LodReplay(Renderer& r, std::function<CameraPose(int)> pose, std::vector<uint32_t> expected);
  void restart();  // back to S0, before frame 0
  void advanceTo(int frame);
  int next() const { return next_; }  // the first frame not replayed yet

 private:
  LodState& lod_;
  std::function<CameraPose(int)> pose_;
  std::vector<uint32_t> expected_;
  int next_ = 0;
};

// Draws frozen for its lifetime (and unfreezes when a measurement throws); a path without a LOD
// state has nothing to freeze.
struct FrozenLod {
  LodState* lod;
  explicit FrozenLod(Renderer& r) : lod(r.hasLodState() ? &r.lodState() : nullptr) {
    if (lod) lod->setFrozen(true);
  }
  ~FrozenLod() {
    if (lod) lod->setFrozen(false);
  }
  FrozenLod(const FrozenLod&) = delete;
  FrozenLod& operator=(const FrozenLod&) = delete;
};

}  // namespace lb
