#pragma once
// Surplus (docs/design.md, What is measured): the scheme's triangles / the triangles `errbound` needs to reach
// the same measured error statistic (p95 of the error map, px) on the same frame. errbound's
// max_error_px is bisected (in log scale over its range [0.1, 64]) with one error-map render per
// step until errbound's p95 is within 2% of the scheme's (docs/results-format.md, "Surplus").
#include <cstdint>
#include <memory>
#include <vector>

#include "render/renderer.h"

namespace lb {

struct Context;
struct CameraPose;
struct Heightfield;

struct SurplusResult {
  double surplus = 0;          // NaN when no bound brackets the target (see matched)
  double boundPx = 0;          // errbound's max_error_px at the match (NaN if none)
  double errboundP95 = 0;      // errbound's measured p95 there (px)
  double errboundTriangles = 0;
  // 1: a bound within 2%; 0: none within 2% (p95 jumps with the discrete levels), so errbound's
  // triangles are interpolated linearly in p95 between the two closest bounds on either side;
  // -1: the target lies outside what errbound reaches over [0.1, 64] px (surplus NaN).
  int matched = -1;
  int renders = 0;
};

// p95 of the error map over pixels with terrain (values >= 0), as measureFrame's err_p95_px.
double errorP95(const std::vector<float>& errorMap);

// Keeps one errbound renderer per terrain and settings across the measured frames of a case.
class SurplusMatcher {
 public:
  SurplusResult match(Context& ctx, const Heightfield& terrain, const RenderSettings& settings, const CameraPose& pose,
                      double targetP95, uint64_t schemeTriangles);

 private:
  std::unique_ptr<Renderer> renderer_;
  const Heightfield* terrain_ = nullptr;
  RenderSettings settings_;
};

}  // namespace lb
