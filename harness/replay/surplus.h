#pragma once
// Surplus (docs/design.md, What is measured): the scheme's triangles / the triangles the error-bounded scheme (the
// registered scheme whose main parameter has role MainParamRole::ErrorBoundPx) needs to reach the same measured error
// statistic (p95 of the error map, px) on the same frame. Its bound is searched (in log scale over
// the parameter's range: proportional steps, then regula falsi in the bracket) with one error-map
// render per step until its p95 is within 2% of the scheme's (docs/results-format.md, "Surplus").
#include <cstdint>
#include <memory>
#include <vector>

#include "render/renderer.h"

namespace lb {

struct Context;
struct CameraPose;
struct Heightfield;
class MeasureGpu;

struct SurplusResult {
  double surplus = 0;   // NaN when no bound brackets the target (see matched)
  double boundPx = 0;   // the error-bounded scheme's bound at the match (NaN if none)
  double boundP95 = 0;  // its measured p95 there (px)
  double boundTriangles = 0;
  // 1: a bound within 2%; 0: none within 2% (p95 jumps with the discrete levels), so its
  // triangles are interpolated linearly in p95 between the two closest bounds on either side;
  // -1: the target lies outside what the bound's range reaches (surplus NaN).
  int matched = -1;
  int renders = 0;
};

// p95 of the error map over pixels with terrain (values >= 0), as measureFrame's err_p95_px.
double errorP95(const std::vector<float>& errorMap);

// Keeps one error-bounded renderer per terrain and settings across the measured frames of a case.
class SurplusMatcher {
 public:
  // With `gpu`, each trial's error map stays on the device and its p95 is reduced there.
  SurplusResult match(Context& ctx, const Heightfield& terrain, const RenderSettings& settings, const CameraPose& pose,
                      double targetP95, uint64_t schemeTriangles, MeasureGpu* gpu = nullptr);

 private:
  std::unique_ptr<Renderer> renderer_;
  const Heightfield* terrain_ = nullptr;
  RenderSettings settings_;
};

}  // namespace lb
