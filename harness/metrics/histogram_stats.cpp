#include "metrics/histogram_stats.h"

#include <algorithm>

#include "render/frame_data.h"

namespace lb {
namespace {

constexpr int kBins = 15;
constexpr int kUnder1pxBins = 4;  // bins 0..3 end at 1/8, 1/4, 1/2, 1 px

// log2 of bin k's lower edge; every bin spans one octave (see the header for bins 0 and 14).
double binLog2Low(int k) {
  return k == 0 ? -4.0 : double(k - 4);
}

}  // namespace

HistogramStats histogramStats(const TriangleHistogram& hist, double targetArea, double areaSum) {
  HistogramStats s;
  for (uint64_t c : hist.bins) s.binned += c;
  if (s.binned == 0) return s;
  const double total = double(s.binned);

  uint64_t under = 0;
  for (int k = 0; k < kUnder1pxBins; ++k) under += hist.bins[size_t(k)];
  s.fracUnder1px = double(under) / total;

  double half = total / 2, below = 0;
  for (int k = 0; k < kBins; ++k) {
    double c = double(hist.bins[size_t(k)]);
    if (c > 0 && below + c >= half) {
      s.medianArea = std::exp2(binLog2Low(k) + (half - below) / c);
      break;
    }
    below += c;
  }

  if (!std::isnan(areaSum)) {
    s.meanArea = areaSum / total;
    s.meanExact = true;
  } else {
    double sum = 0;
    for (int k = 0; k < kBins; ++k) sum += double(hist.bins[size_t(k)]) * std::exp2(binLog2Low(k) + 0.5);
    s.meanArea = sum / total;
  }

  if (targetArea > 0) {  // false for NaN
    const double lo = std::log2(targetArea) - 1, hi = std::log2(targetArea) + 1;
    double near = 0;
    for (int k = 0; k < kBins; ++k) {
      double overlap = std::min(hi, binLog2Low(k) + 1) - std::max(lo, binLog2Low(k));
      near += double(hist.bins[size_t(k)]) * std::clamp(overlap, 0.0, 1.0);
    }
    s.fracNearTarget = near / total;
  }
  return s;
}

}  // namespace lb
