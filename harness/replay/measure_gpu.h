#pragma once
// Measurement at the GPU's speed: the live frame, its error map, popping's two frames and the ray-cast
// truth stay in device buffers; the ray cast (metrics/gpu_raycast.h) and the reductions
// (metrics/gpu_reduce.h) run as compute passes and only numbers come back. Images are read back only
// where a crack candidate needs the CPU's flood fill or a caller asked for the pixels.
#include <memory>
#include <vector>

#include "camera/camera_path.h"
#include "config/measure_spec.h"
#include "metrics/gpu_flip.h"
#include "metrics/gpu_raycast.h"
#include "metrics/gpu_reduce.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct Heightfield;

// Whether measureFrame takes this path: "gpu" and "cpu" as asked; "auto" on every device but a CPU
// rasterizer. On lavapipe the "GPU" runs on the same CPU cores, and the CPU path with its truth cache
// on disk measured faster there (README, Measurement passes: 106 against 127 ms a measured frame on
// five of the default job's cases; the GPU path's SSIM and ray cast are the slower parts).
bool measureOnGpu(const MeasureSpec& spec, const Context& ctx);

// One per terrain and resolution, kept across a sweep's cases (ReferenceCache::gpu).
class MeasureGpu {
 public:
  MeasureGpu(Context& ctx, int width, int height);
  // The ray-cast truth of `pose` into `truth` (cast again only when the pose changes). The ray cast
  // is made on first use, so passes that never read the truth (histogram, error) measure a terrain
  // past its limits; there it throws FeatureMissing, for the caller to report. `terrain`: the
  // case's own, the same heights as the constructor's (the cache keys on them).
  void castTruth(const Heightfield& terrain, const CameraPose& pose);
  RgbaImage readImage(const Buffer& b);
  std::vector<float> readFloats(const Buffer& b);
  // FLIP's passes at viewing distance `ppd` (made on first use, again for another distance).
  GpuFlip& flip(double ppd);

  GpuReduce reduce;
  // width * height words each; STORAGE for the passes, TRANSFER_DST for the renderer's copy,
  // TRANSFER_SRC for read-backs.
  Buffer shaded, truth, error, popFrozen, popLive, surplusError;

 private:
  Context& ctx_;
  std::unique_ptr<GpuRaycast> raycast_;
  int width_, height_;
  bool haveTruth_ = false;
  CameraPose truthPose_;
  Buffer staging_;  // host-visible, for read-backs
  std::unique_ptr<GpuFlip> flip_;
};

}  // namespace lb
