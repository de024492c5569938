// GpuReduce's two calls: the passes each records, and the statistics made from the words read back.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "metrics/gpu_reduce.h"
#include "shaders/reduce_params.h"
#include "stats.h"
#include "vk/resources.h"

namespace lb {

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

uint64_t word64(const std::vector<uint32_t>& w, int at) {
  return uint64_t(w[size_t(at)]) | uint64_t(w[size_t(at) + 1]) << 32;
}

// The value of rank i (0-based, ascending) from a histogram's counts, where every value of bin b is `value(b)`.
template <typename Value>
double fromHistogram(const uint32_t* counts, int bins, size_t i, Value value) {
  size_t below = 0;
  for (int b = 0; b < bins; ++b) {
    if (i < below + counts[b]) return value(b, i - below, counts[b]);
    below += counts[b];
  }
  throw std::logic_error("GpuReduce: a rank beyond the histogram's count");
}

}  // namespace

GpuImageStats GpuReduce::compare(const Buffer& a, const Buffer& b, int threshold, bool ssim, int reach) {
  if (threshold < 0 || reach < 0) throw std::invalid_argument("GpuReduce::compare: threshold and reach must be >= 0");
  if (ssim && ssimGroupsX_ == 0) throw std::invalid_argument("SSIM needs images of at least 11x11");
  bind(a, b);
  const ReducePush push{uint32_t(width_), uint32_t(height_), uint32_t(threshold), uint32_t(reach)};
  const uint32_t ssimGroups = ssim ? ssimGroupsX_ * ssimGroupsY_ : 0;
  run(ssimGroups * (float64_ ? 2 : 1), [&](VkCommandBuffer cmd) {
    dispatch(cmd, image_, imageGroups_, 1, push);
    if (ssim) dispatch(cmd, ssim_, ssimGroupsX_, ssimGroupsY_, push);  // writes other words: no barrier
  });
  const std::vector<uint32_t>& w = words_;
  const size_t n = size_t(width_) * size_t(height_);
  GpuImageStats s;
  ImageError& e = s.e;
  // The same integer sums compareImages adds in double (exactly, below 2^53), so the same results.
  const double sq = double(word64(w, LB_RED_SUM_SQ)), absSum = double(word64(w, LB_RED_SUM_ABS));
  const double mse = sq / double(n * 3);
  e.psnrDb = mse == 0 ? kPsnrIdentical : std::min(kPsnrIdentical, 10.0 * std::log10(255.0 * 255.0 / mse));
  e.meanAbsDiff = absSum / double(n * 3);
  e.fractionOver = double(w[LB_RED_OVER]) / double(n);
  e.changedPixels = long(w[LB_RED_CHANGED]);
  uint32_t hist[256];
  std::copy(w.begin() + LB_RED_DIFF_HIST, w.begin() + LB_RED_DIFF_HIST + 256, hist);
  hist[0] = uint32_t(n) - w[LB_RED_CHANGED];  // the pass leaves bin 0 to the host
  e.p99AbsDiff = percentileOfSorted(n, 99, [&](size_t i) {
    return fromHistogram(hist, 256, i, [](int bin, size_t, uint32_t) { return double(bin); });
  });
  e.ssim = kNan;
  if (ssim) {
    double total = 0;
    for (uint32_t g = 0; g < ssimGroups; ++g)
      total += float64_ ? std::bit_cast<double>(word64(w, LB_RED_PARTIALS + 2 * int(g)))
                        : double(std::bit_cast<float>(w[LB_RED_PARTIALS + g]));
    e.ssim = total / (double(width_ - 2 * LB_SSIM_RADIUS) * double(height_ - 2 * LB_SSIM_RADIUS));
  }
  s.coverageMissing = long(w[LB_RED_MISSING]);
  s.coverageExtra = long(w[LB_RED_EXTRA]);
  s.crackCandidates = long(w[LB_RED_CANDIDATES]);
  s.truthTerrain = long(w[LB_RED_TRUTH_TERRAIN]);
  return s;
}

GpuErrorStats GpuReduce::errorStats(const Buffer& error) {
  bind(error, error);
  const ReducePush push{uint32_t(width_), uint32_t(height_), 0, 0};
  run(errorGroups_, [&](VkCommandBuffer cmd) {
    const VkPipelineStageFlags2 compute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    const VkAccessFlags2 readWrite = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
    dispatch(cmd, error_, errorGroups_, 1, push);
    memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute, readWrite);
    dispatch(cmd, select_, 1, 1, push);
    memoryBarrier(cmd, compute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, compute, readWrite);
    dispatch(cmd, fine_, errorGroups_, 1, push);
  });
  const std::vector<uint32_t>& w = words_;
  GpuErrorStats s;
  s.count = long(w[LB_RED_ERR_COUNT]);
  if (s.count == 0) {
    s.mean = s.p95 = s.max = kNan;
    return s;
  }
  s.max = double(std::bit_cast<float>(w[LB_RED_ERR_MAX]));
  double total = 0;
  for (uint32_t g = 0; g < errorGroups_; ++g) total += double(std::bit_cast<float>(w[LB_RED_PARTIALS + g]));
  s.mean = total / double(s.count);
  // A rank's value: its exponent bin from the coarse histogram, then its 2^-10-wide mantissa bin
  // from the fine one, with the bin's values spread evenly inside it (k-th of `count` at (k + 0.5) /
  // count of the width). Between two ranks the estimate is off by at most 2^-10 of the value.
  const uint32_t* fine = &w[LB_RED_FINE_HIST];
  auto valueOfRank = [&](size_t i) {
    return fromHistogram(&w[LB_RED_COARSE_HIST], 256, i, [&](int exponent, size_t within, uint32_t) {
      int j = 0;
      while (j < 3 && w[size_t(LB_RED_ERR_SELECT + j)] != uint32_t(exponent)) ++j;
      if (j == 3) throw std::logic_error("GpuReduce: the p95's ranks fell outside the selected exponent bins");
      if (exponent == 255) return double(std::numeric_limits<float>::infinity());
      return fromHistogram(fine + j * LB_RED_FINE_BINS, LB_RED_FINE_BINS, within,
                           [&](int mantissa, size_t k, uint32_t count) {
                             const uint32_t bits = uint32_t(exponent) << 23 | uint32_t(mantissa) << 13;
                             const double lo = std::bit_cast<float>(bits), hi = std::bit_cast<float>(bits + (1u << 13));
                             return std::min(s.max, lo + (double(k) + 0.5) / double(count) * (hi - lo));
                           });
    });
  };
  s.p95 = percentileOfSorted(size_t(s.count), 95, valueOfRank);
  return s;
}

}  // namespace lb
