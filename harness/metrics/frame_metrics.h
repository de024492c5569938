#pragma once
// The metric values of one measured frame, and the names they go by in result files
// (docs/results-format.md). replay/measure.h fills them; results/write.h records them.
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "metrics/image_metrics.h"
#include "render/frame_data.h"

namespace lb {

// Metric values in the order of docs/results-format.md; NaN = unavailable.
struct FrameMetrics {
  int frame = 0;
  std::vector<std::pair<std::string, double>> values;
  bool hasHistogram = false;
  TriangleHistogram histogram;
  RgbaImage shaded, reference;  // kept for crack masks and image strips; reference = ground truth
  std::vector<float> errorMap;
  std::vector<uint8_t> crackMask;
  std::vector<float> flipMap;  // per-pixel FLIP against the truth (metrics/flip.h), where the image pass ran
  std::map<std::string, std::string> unavailable;  // pass -> why the device cannot run it (its values are null)
  // Wall seconds of each measurement pass on this frame (run.json measure_costs, the report's
  // context table): where a measured frame's time goes.
  std::map<std::string, double> costs;
};

// What image metrics (img_*), crack pixels and the images that show them compare against:
// recorded in every case record as "image_reference" (docs/results-format.md).
constexpr const char* kImageReference = "raycast";

// The frame's value of metric `key`; NaN when the frame has none (pass off or unavailable).
double metricValue(const FrameMetrics& m, const std::string& key);

// Column names of the measurement part of frames.csv, in order.
std::vector<std::string> metricColumns();

}  // namespace lb
