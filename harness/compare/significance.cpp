#include "compare/significance.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>

#include "random.h"
#include "stats.h"

namespace lb {

MannWhitney mannWhitneyU(const std::vector<double>& x, const std::vector<double>& y) {
  MannWhitney r;
  const double n1 = double(x.size()), n2 = double(y.size()), n = n1 + n2;
  if (x.empty() || y.empty()) return r;
  // Rank the pooled sample, tied values sharing their mean rank.
  std::vector<std::pair<double, bool>> all;  // value, from x
  all.reserve(x.size() + y.size());
  for (double v : x) all.push_back({v, true});
  for (double v : y) all.push_back({v, false});
  std::sort(all.begin(), all.end(), [](auto& a, auto& b) { return a.first < b.first; });
  double rankSumX = 0, tieTerm = 0;  // tieTerm: sum over tie groups of t^3 - t
  for (size_t i = 0; i < all.size();) {
    size_t j = i;
    while (j < all.size() && all[j].first == all[i].first) ++j;
    const double t = double(j - i), meanRank = (double(i + 1) + double(j)) / 2.0;
    for (size_t k = i; k < j; ++k)
      if (all[k].second) rankSumX += meanRank;
    tieTerm += t * t * t - t;
    i = j;
  }
  r.u = rankSumX - n1 * (n1 + 1) / 2.0;
  const double u = std::max(r.u, n1 * n2 - r.u);  // two-sided: the larger U, as scipy does
  const double mu = n1 * n2 / 2.0;
  const double var = n1 * n2 / 12.0 * ((n + 1) - tieTerm / (n * (n - 1)));
  if (!(var > 0)) return r;  // every value tied: no evidence either way
  r.z = (u - mu - 0.5) / std::sqrt(var);
  r.p = std::min(1.0, std::erfc(r.z / std::sqrt(2.0)));  // 2 * normal survival function
  return r;
}

double median(std::vector<double> values) {
  return percentile(std::move(values), 50);
}

namespace {

// Median by selection rather than a full sort (the bootstrap takes thousands); the same value as
// percentile(v, 50), whose midpoint is hi - (hi - lo) * 0.5.
double medianInPlace(std::vector<double>& v) {
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(mid), v.end());
  const double hi = v[mid];
  if (v.size() % 2) return hi;
  const double lo = *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(mid));
  return hi - (hi - lo) * 0.5;
}

double resampledMedian(const std::vector<double>& v, SplitMix64& rng, std::vector<double>& scratch) {
  scratch.resize(v.size());
  for (double& s : scratch) s = v[rng.below(v.size())];
  return medianInPlace(scratch);
}

}  // namespace

RatioInterval bootstrapMedianRatio(const std::vector<double>& baseline, const std::vector<double>& candidate,
                                   double confidence, int resamples, uint64_t seed) {
  assert(!baseline.empty() && !candidate.empty() && resamples > 0);
  RatioInterval r;
  const double mb = median(baseline);
  assert(mb > 0);
  r.ratio = median(candidate) / mb;
  SplitMix64 rng{seed};
  std::vector<double> ratios, scratch;
  ratios.reserve(size_t(resamples));
  for (int i = 0; i < resamples; ++i) {
    const double b = resampledMedian(baseline, rng, scratch);
    const double c = resampledMedian(candidate, rng, scratch);
    if (b > 0) ratios.push_back(c / b);
  }
  const double tail = (1.0 - confidence) / 2.0 * 100.0;
  r.lo = percentile(ratios, tail);
  r.hi = percentile(ratios, 100.0 - tail);
  return r;
}

namespace {

// Continued fraction of the incomplete beta function (modified Lentz; Numerical Recipes 6.4).
double betaContinuedFraction(double a, double b, double x) {
  const double tiny = 1e-300;
  double c = 1, d = 1 - (a + b) * x / (a + 1);
  if (std::abs(d) < tiny) d = tiny;
  d = 1 / d;
  double h = d;
  for (int m = 1; m <= 300; ++m) {
    double m2 = 2.0 * m, aa = m * (b - m) * x / ((a - 1 + m2) * (a + m2));
    d = 1 + aa * d, c = 1 + aa / c;
    if (std::abs(d) < tiny) d = tiny;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1 + m2));
    d = 1 + aa * d, c = 1 + aa / c;
    if (std::abs(d) < tiny) d = tiny;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    double del = d * c;
    h *= del;
    if (std::abs(del - 1) < 1e-15) break;
  }
  return h;
}

double incompleteBeta(double a, double b, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  double lbt = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log(1 - x);
  if (x < (a + 1) / (a + b + 2)) return std::exp(lbt) * betaContinuedFraction(a, b, x) / a;
  return 1 - std::exp(lbt) * betaContinuedFraction(b, a, 1 - x) / b;
}

double meanOf(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / double(v.size());
}

double varianceOf(const std::vector<double>& v) {  // sample variance (n - 1)
  double m = meanOf(v), s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() > 1 ? s / double(v.size() - 1) : 0;
}

}  // namespace

double studentTwoSidedP(double t, double df) {
  if (!std::isfinite(t)) return 0;
  return incompleteBeta(df / 2, 0.5, df / (df + t * t));
}

double studentQuantile(double confidence, double df) {
  double lo = 0, hi = 1e6;
  for (int i = 0; i < 200; ++i) {
    double mid = (lo + hi) / 2;
    (studentTwoSidedP(mid, df) > 1 - confidence ? lo : hi) = mid;
  }
  return (lo + hi) / 2;
}

RoundTest roundTest(const std::vector<double>& b, const std::vector<double>& c, bool paired, double confidence) {
  assert(b.size() >= 2 && c.size() >= 2 && (!paired || b.size() == c.size()));
  std::vector<double> lb, lc;
  for (double v : b) lb.push_back(std::log(v));
  for (double v : c) lc.push_back(std::log(v));
  RoundTest r;
  double diff, se;
  if (paired) {
    std::vector<double> d;
    for (size_t i = 0; i < lb.size(); ++i) d.push_back(lc[i] - lb[i]);
    diff = meanOf(d);
    se = std::sqrt(varianceOf(d) / double(d.size()));
    r.df = double(d.size() - 1);
  } else {
    diff = meanOf(lc) - meanOf(lb);
    double vb = varianceOf(lb) / double(lb.size()), vc = varianceOf(lc) / double(lc.size());
    se = std::sqrt(vb + vc);
    // Welch-Satterthwaite degrees of freedom.
    r.df = se > 0 ? (vb + vc) * (vb + vc) / (vb * vb / double(lb.size() - 1) + vc * vc / double(lc.size() - 1))
                  : double(lb.size() + lc.size() - 2);
  }
  r.ratio = std::exp(diff);
  if (!(se > 0)) {  // no spread between rounds: equal means no evidence, different is certain
    r.p = diff == 0 ? 1 : 0;
    r.lo = r.hi = r.ratio;
    return r;
  }
  r.t = diff / se;
  r.p = studentTwoSidedP(r.t, r.df);
  double q = studentQuantile(confidence, r.df);
  r.lo = std::exp(diff - q * se);
  r.hi = std::exp(diff + q * se);
  return r;
}

}  // namespace lb
