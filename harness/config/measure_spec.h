#pragma once
// The "measure" section of a config: which measurement passes run, and on which frames.
#include <set>
#include <string>

#include "shaders/flip_params.h"

namespace lb {

struct MeasureSpec {
  int every = 0;  // measure every n-th frame (0 = no measurement frames)
  std::set<std::string> passes = {"histogram", "error", "image", "cracks", "popping", "surplus"};
  int diffThreshold = 16;  // per-channel difference (0..255) counted by img_frac_over
  // Where the ray-cast truth and the frame statistics run (replay/measure_gpu.h): "gpu" keeps images
  // on the device and reads back only numbers; "cpu" reads images back and reduces them on the host;
  // "auto" picks the faster of the two for the device (measureOnGpu).
  std::string compute = "auto";
  // FLIP's viewing distance in pixels per degree of visual angle (metrics/flip.h), for the frames
  // the image pass measures.
  double flipPpd = LB_FLIP_DEFAULT_PPD;
  bool on(const std::string& pass) const { return every > 0 && passes.count(pass) > 0; }
};
const std::set<std::string>& allMeasurePasses();

}  // namespace lb
