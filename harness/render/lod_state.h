#pragma once
// The LOD state a draw path keeps across frames (the GPU-indirect path's: a tree its compute passes
// refine a little every frame), as harness/replay/lod_replay.h drives it: reset, snapshot and
// restore it so repetitions and replays start alike, run one frame's update alone, and draw frozen.
// Every call waits for the frames in flight first.
#include <cstdint>
#include <vector>

namespace lb {

struct CameraPose;
struct GpuLod;

class LodState {
 public:
  virtual ~LodState() = default;
  virtual void reset() = 0;     // the scheme's initial state
  virtual void snapshot() = 0;  // copies the state aside
  virtual void restore() = 0;   // copies the snapshot back
  virtual std::vector<uint32_t> read() = 0;
  virtual void load(const std::vector<uint32_t>& words) = 0;  // the whole state, e.g. another renderer's
  // A second copy aside on the device, beside the snapshot, and back: what read() and load() do for
  // a caller that puts this renderer's own state back, without the state (up to 64 MiB) crossing to
  // the host and back.
  virtual void keep() = 0;
  virtual void putBack() = 0;
  // One frame's LOD passes alone for `pose`; returns the instance count they left.
  virtual uint32_t update(const CameraPose& pose) = 0;
  // While frozen, frames draw the last update's instances without running the passes, so
  // measurement passes see the state a timed frame drew.
  virtual void setFrozen(bool frozen) = 0;
  virtual uint32_t overflow() const = 0;     // instances the last update left beyond the capacity (none drawn)
  virtual const GpuLod& gpuLod() const = 0;  // the scheme's description: capacity, convergence limit, facts
};

}  // namespace lb
