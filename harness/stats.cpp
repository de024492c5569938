#include "stats.h"

#include <algorithm>
#include <cmath>

namespace lb {
namespace {

// NaN sorts last: std::sort needs a strict weak order, and plain < on NaN breaks it (undefined
// behaviour, in practice out-of-bounds reads), so a stray NaN frame time must not crash a run.
bool lessNanLast(double a, double b) {
  return std::isnan(b) ? !std::isnan(a) : a < b;
}

// values must be sorted with lessNanLast and non-empty.
double percentileSorted(const std::vector<double>& sorted, double q) {
  return percentileOfSorted(sorted.size(), q, [&](size_t i) { return sorted[i]; });
}

}  // namespace

double percentileOfSorted(size_t n, double q, const std::function<double(size_t)>& at) {
  q = std::min(100.0, std::max(0.0, q));  // NaN q ends up as 0
  const double rank = q / 100.0 * static_cast<double>(n - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(lo + 1, n - 1);
  const double a = at(lo), frac = rank - static_cast<double>(lo);
  if (frac == 0.0) return a;
  // numpy's _lerp: interpolating from the nearer end keeps results bit-identical to
  // np.percentile(..., method="linear"), so analysis scripts can cross-check our numbers.
  const double b = at(hi), diff = b - a;
  return frac >= 0.5 ? b - diff * (1.0 - frac) : a + diff * frac;
}

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end(), lessNanLast);
  return percentileSorted(values, q);
}

Summary summarize(const std::vector<double>& values) {
  Summary s;
  if (values.empty()) return s;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end(), lessNanLast);
  s.count = static_cast<int>(sorted.size());
  s.min = sorted.front();
  s.max = sorted.back();
  s.median = percentileSorted(sorted, 50);
  s.p5 = percentileSorted(sorted, 5);
  s.p95 = percentileSorted(sorted, 95);
  s.p99 = percentileSorted(sorted, 99);

  double sum = 0;
  for (double v : sorted) sum += v;
  s.mean = sum / s.count;
  // Two passes rather than sum of squares: frame times are large and nearly equal, exactly
  // the case where E[x^2] - E[x]^2 cancels catastrophically.
  double sq = 0;
  for (double v : sorted) sq += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(sq / s.count);  // population: the run is the whole population we report on
  return s;
}

}  // namespace lb
