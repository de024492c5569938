#pragma once
// Measurement passes of one frame (docs/design.md, What is measured), run after a case's timing frames so they
// never perturb the timings: histogram, screen-space error, image error against the ray-cast
// ground truth, cracks, popping, surplus.
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "camera/camera_path.h"
#include "config/measure_spec.h"
#include "metrics/frame_metrics.h"
#include "metrics/image_metrics.h"
#include "render/renderer.h"
#include "replay/popping.h"
#include "replay/raycast_cache.h"
#include "replay/surplus.h"

namespace lb {

struct Context;
struct Heightfield;

// `older`: the LOD of frames t-2 and t-3 for popping at those lags (replay/popping.h OlderLod); without
// it the pop2_* and pop3_* keys are left out.
// `popBefore`: a stateful LOD's previous state drawn from this frame's view (replay/lod_replay.h),
// which popping compares with this frame; null: popping draws the previous LOD camera's selection.
// keepPixels: the frame's shaded image, truth and error map in FrameMetrics even where the statistics
// were reduced on the GPU (replay/measure_gpu.h; the crack mask is always there when cracks run).
FrameMetrics measureFrame(Context& ctx, Renderer& renderer, const Scheme& scheme, const ParamValues& params,
                          const Heightfield& terrain, const std::string& terrainKey, const MeasureSpec& spec,
                          ReferenceCache& refs, int frame, const CameraPose& previous, const CameraPose& current,
                          const RgbaImage* popBefore = nullptr, bool keepPixels = false,
                          const OlderLod* older = nullptr);

// Error map visualisation: 0 px black .. >= 8 px white (sqrt scale), sky (kSkyRgba) where no terrain.
RgbaImage errorImage(const std::vector<float>& error, int width, int height);

}  // namespace lb
