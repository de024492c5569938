#pragma once
// The "match" section of a config: the target a matched comparison searches each case's main
// parameter for (replay/matched.h runs the search).
#include <string>

namespace lb {

struct MatchSpec {
  std::string metric;   // "" (off) | "triangles" | "err_mean_px" | "err_p95_px"
  double value = 0;     // target: mean over the frames of triangles, mean error or p95 error (pixels)
  int frames = 8;       // evaluation frames spread evenly over the path
  int iterations = 12;  // bisection steps
  // Tuned search (replay/matched.h tuneAndMatch): every scheme searched over its registry's tuning
  // space (schemes/registry.h defaultTuneSpace) unless its entry lists its own "tune".
  bool tune = false;
  // Evaluations a scheme's whole search may use (0: 4 x (iterations + 2)), the same for every
  // scheme: each of a space's K configurations gets min(iterations, max(2, budget / K - 2)) steps.
  int budget = 0;
  bool on() const { return !metric.empty(); }
};

}  // namespace lb
