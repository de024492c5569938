#pragma once
// Popping (docs/design.md, What is measured): the visual change between two frames caused only by the LOD update.
// The current pose is rendered twice, once with the LOD camera frozen at the previous pose (the
// NVIDIA sample's "Eye only" mode: the centre of projection moves, the LOD does not) and once with
// live LOD; camera motion is the same in both, so every difference comes from the levels changing.
#include <vector>

#include "camera/camera_path.h"
#include "metrics/image_metrics.h"

namespace lb {

class Renderer;
class MeasureGpu;

struct PopResult {
  double mean = 0;   // mean over pixels of the mean absolute RGB difference, 0..255
  double p99 = 0;    // 99th percentile of the per-pixel largest channel difference, 0..255
  long changed = 0;  // pixels with any channel difference
};

// Renders `current` shaded with LOD camera `previous`, then with LOD camera `current`, both culling
// with the current (projection) camera's frustum so that the old frustum's culling leaves no holes
// (Renderer::CullCamera::View, restored afterwards), and compares them with compareImages. Uses the
// renderer's scheme; waits for frames in flight. previous == current gives exactly zero (the
// renderer is deterministic). Back-face tests that use the LOD eye (phong) still use `previous`.
// With `gpu`, both frames stay on the device and are compared there (the same numbers, exactly).
// Popping at lags 2 .. kPopLags (pop2_*, pop3_*): frame t against the LOD of frame t - k drawn from
// t's camera, as lag 1 does with frame t - 1. A LOD that flickers between states shows at some lags
// and not at others (one alternating every frame pops at lags 1 and 3, not at 2).
constexpr int kPopLags = 3;
struct OlderLod {
  // Index k - 2 for lag k, as far as frame t - k exists:
  std::vector<CameraPose> poses;  // the LOD camera of frame t - k (a LOD decided from the camera)
  std::vector<RgbaImage> images;  // a stateful LOD: its state of frame t - k drawn from t's view (used over poses)
};

PopResult measurePopping(Renderer& renderer, const CameraPose& previous, const CameraPose& current,
                         MeasureGpu* gpu = nullptr);
// The same for several LOD cameras at once (lags 1, 2, 3): the live frame drawn once.
std::vector<PopResult> measurePopping(Renderer& renderer, const std::vector<CameraPose>& previous,
                                      const CameraPose& current, MeasureGpu* gpu = nullptr);

}  // namespace lb
