#pragma once
// Measurement passes of one frame (design section 6), run after a case's timing frames so they
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
#include "metrics/image_metrics.h"
#include "metrics/raycast_cache.h"
#include "metrics/surplus.h"
#include "render/renderer.h"

namespace lb {

struct Context;
struct Heightfield;

struct MeasureSpec {
  int every = 0;  // measure every n-th frame (0 = no measurement frames)
  std::set<std::string> passes = {"histogram", "error", "image", "cracks", "popping", "surplus"};
  int diffThreshold = 16;  // per-channel difference (0..255) counted by img_frac_over
  bool on(const std::string& pass) const { return every > 0 && passes.count(pass) > 0; }
};
const std::set<std::string>& allMeasurePasses();

// Metric values in the order of docs/results-format.md; NaN = unavailable.
struct FrameMetrics {
  int frame = 0;
  std::vector<std::pair<std::string, double>> values;
  bool hasHistogram = false;
  TriangleHistogram histogram;
  RgbaImage shaded, reference;    // kept for crack masks and image strips; reference = ground truth
  std::vector<float> errorMap;
  std::vector<uint8_t> crackMask;
  std::map<std::string, std::string> unavailable;  // pass -> why the device cannot run it (its values are null)
};

// What image metrics (img_*), crack pixels and the images that show them compare against:
// recorded in every case record as "image_reference" (docs/results-format.md).
constexpr const char* kImageReference = "raycast";

FrameMetrics measureFrame(Context& ctx, Renderer& renderer, const Scheme& scheme, const ParamValues& params,
                          const Heightfield& terrain, const std::string& terrainKey, const MeasureSpec& spec,
                          ReferenceCache& refs, int frame, const CameraPose& previous, const CameraPose& current);

// Column names of the measurement part of frames.csv, in order.
std::vector<std::string> metricColumns();
// Error map visualisation: 0 px black .. >= 8 px white (sqrt scale), sky (kSkyRgba) where no terrain.
RgbaImage errorImage(const std::vector<float>& error, int width, int height);

}  // namespace lb
