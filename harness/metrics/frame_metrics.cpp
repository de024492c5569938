#include "metrics/frame_metrics.h"

#include <cmath>

#include "schemes/registry.h"
#include "shaders/shared.h"

namespace lb {

double metricValue(const FrameMetrics& m, const std::string& key) {
  for (auto& [k, v] : m.values)
    if (k == key) return v;
  return std::nan("");
}

std::vector<std::string> metricColumns() {
  std::vector<std::string> c;
  for (int i = 0; i < LB_HIST_BINS; ++i) c.push_back("hist_" + std::to_string(i));
  for (const char* n : {"hist_offscreen",
                        "hist_backfacing",
                        "tri_area_mean",
                        "tri_area_median",
                        "tri_frac_under_1px",
                        "tri_frac_near_target",
                        "err_mean_px",
                        "err_p95_px",
                        "err_max_px",
                        "img_psnr_db",
                        "img_ssim",
                        "img_mad",
                        "img_frac_over",
                        "cracks_analytic",
                        "cracks_pixels",
                        "pop_mean",
                        "pop_p99",
                        "pop_changed",
                        "surplus",
                        "saturated_patches"})
    c.push_back(n);
  for (const char* n : {"surplus_bound_px", "surplus_p95_px", "surplus_triangles", "surplus_matched"}) c.push_back(n);
  // Every registered scheme's own counters, so all cases share one set of columns.
  for (const Scheme* s : allSchemes())
    for (const SchemeCounter& counter : s->info().counters) c.push_back(counter.frameKey);
  // Newer columns go last, so the earlier ones keep their positions.
  for (const char* n : {"coverage_missing_px", "coverage_extra_px", "coverage_truth_px"}) c.push_back(n);
  for (const char* n :
       {"flip_mean", "flip_p95", "pop2_mean", "pop2_p99", "pop2_changed", "pop3_mean", "pop3_p99", "pop3_changed"})
    c.push_back(n);
  return c;
}

}  // namespace lb
