#pragma once
// Statistics derived from a triangle-size histogram (docs/design.md, What is measured): mean/median area,
// the fraction under 1 px and the fraction within a factor 2 of a scheme's target area.
#include <cmath>
#include <cstdint>

namespace lb {

struct TriangleHistogram;

// Every value is over the binned triangles only (on-screen and front-facing: the 15 bins);
// NaN when there are none (or, for fracNearTarget, when no target is given).
struct HistogramStats {
  uint64_t binned = 0;
  double fracUnder1px = NAN;    // exact: bins 0..3 (< 1/8, [1/8,1/4), [1/4,1/2), [1/2,1)) / binned
  double medianArea = NAN;      // estimate, px: log-linear interpolation inside the median bin
  double meanArea = NAN;        // px: areaSum / binned when areaSum is known, else an estimate
  bool meanExact = false;       // meanArea came from areaSum
  double fracNearTarget = NAN;  // estimate: area in [target / 2, 2 * target], log-uniform within bins
};

// Estimates assume areas are log-uniform within each bin. Bins 1..13 span one octave
// [2^(k-4), 2^(k-3)); the open-ended bins are given one octave too, bin 0 = [1/16, 1/8) and
// bin 14 = [1024, 2048), so their estimates are only as good as that assumption:
// - medianArea: the bin where the cumulative count reaches binned / 2, at fraction
//   f = (binned / 2 - countBelow) / count of the way through it in log2(area).
// - fracNearTarget: each bin contributes count x (the part of its log-span inside
//   [target / 2, 2 * target]) / (its log-span). Exact when the target's interval sits on bin edges
//   and is entirely inside bins 1..13 (target a power of two from 1/4 to 512).
// - meanArea without areaSum: counts weighted by geometric bin centres lo * sqrt(2) (a log-uniform
//   octave's true mean is lo / ln 2, 2% higher).
// targetArea <= 0 or NaN: no target. areaSum: exact sum of the binned triangles' areas, NaN = unknown.
HistogramStats histogramStats(const TriangleHistogram& hist, double targetArea = NAN, double areaSum = NAN);

}  // namespace lb
