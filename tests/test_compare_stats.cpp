// lodbench compare's statistics: Mann-Whitney U against hand-derived and scipy values, and the
// bootstrap interval's determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "compare/significance.h"
#include "stats.h"

namespace lb {
namespace {

// x entirely below y, n1 = n2 = 5, no ties: U1 = 0, U2 = 25, mu = 12.5, var = 25/12 * 11;
// z = (25 - 12.5 - 0.5) / sqrt(var), p = 2 * sf(z) = erfc(z / sqrt 2) (scipy: 0.012185780355344813).
TEST(CompareStats, MannWhitneyHandComputedNoTies) {
  MannWhitney r = mannWhitneyU({1, 2, 3, 4, 5}, {6, 7, 8, 9, 10});
  EXPECT_DOUBLE_EQ(r.u, 0.0);
  const double z = 12.0 / std::sqrt(25.0 / 12.0 * 11.0);
  EXPECT_NEAR(r.z, z, 1e-12);
  EXPECT_NEAR(r.p, std::erfc(z / std::sqrt(2.0)), 1e-15);
  EXPECT_NEAR(r.p, 0.012185780355344813, 1e-12);
}

// Ties: x = {1,2,2,3,3,3,4}, y = {2,3,3,4,4,5,5,6}. Pairs x > y (ties 1/2): 1 -> 0, 2 -> 0.5 (x2),
// 3 -> 1 + 1 (x3), 4 -> 3 + 1: U1 = 11, U2 = 56 - 11 = 45. Tie groups 2:3, 3:5, 4:3, 5:2 give
// sum(t^3 - t) = 24 + 120 + 24 + 6 = 174; var = 56/12 * (16 - 174/210); z = (45 - 28 - 0.5) / sqrt(var).
// scipy.stats.mannwhitneyu(x, y, alternative="two-sided", method="asymptotic") (scipy 1.10.1):
// statistic 11.0, pvalue 0.04988443697992588.
TEST(CompareStats, MannWhitneyTieCorrectionMatchesScipy) {
  MannWhitney r = mannWhitneyU({1, 2, 2, 3, 3, 3, 4}, {2, 3, 3, 4, 4, 5, 5, 6});
  EXPECT_DOUBLE_EQ(r.u, 11.0);
  const double var = 56.0 / 12.0 * (16.0 - 174.0 / 210.0);
  EXPECT_NEAR(r.z, 16.5 / std::sqrt(var), 1e-12);
  EXPECT_NEAR(r.p, 0.04988443697992588, 1e-12);
}

// Interleaved frame-time-like values without ties; scipy (as above): statistic 15.0, pvalue 0.048539622897320577.
TEST(CompareStats, MannWhitneyFrameTimesMatchScipy) {
  std::vector<double> a = {10.1, 10.4, 10.2, 10.8, 10.3, 10.5, 10.9, 10.0};
  std::vector<double> b = {10.6, 10.7, 11.0, 10.35, 11.2, 10.45, 11.1, 10.65, 10.75};
  MannWhitney r = mannWhitneyU(a, b);
  EXPECT_DOUBLE_EQ(r.u, 15.0);
  EXPECT_NEAR(r.p, 0.048539622897320577, 1e-12);
  // Swapping the samples: U becomes n1 n2 - U, the two-sided p stays.
  MannWhitney s = mannWhitneyU(b, a);
  EXPECT_DOUBLE_EQ(s.u, 72.0 - 15.0);
  EXPECT_DOUBLE_EQ(s.p, r.p);
}

// {1,3,5} vs {2,4}: pairs x > y are 3>2, 5>2, 5>4, so U1 = U2 = 3 = mu; the continuity correction
// makes z negative and p is clipped to 1 (scipy: 1.0).
TEST(CompareStats, MannWhitneyBalancedSamplesGivePOne) {
  MannWhitney r = mannWhitneyU({1, 3, 5}, {2, 4});
  EXPECT_DOUBLE_EQ(r.u, 3.0);
  EXPECT_DOUBLE_EQ(r.p, 1.0);
}

TEST(CompareStats, MannWhitneyDegenerateInputsGivePOne) {
  EXPECT_DOUBLE_EQ(mannWhitneyU({}, {1, 2}).p, 1.0);
  EXPECT_DOUBLE_EQ(mannWhitneyU({1, 2}, {}).p, 1.0);
  EXPECT_DOUBLE_EQ(mannWhitneyU({2, 2, 2}, {2, 2}).p, 1.0);  // every value tied: variance 0
}

std::vector<double> jittered(int n, double scale) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(scale * (1.0 + 0.05 * std::sin(1.7 * i)));
  return v;
}

TEST(CompareStats, BootstrapIsDeterministicAndSeeded) {
  auto a = jittered(60, 1.0), b = jittered(45, 1.1);
  RatioInterval r1 = bootstrapMedianRatio(a, b, 0.99);
  RatioInterval r2 = bootstrapMedianRatio(a, b, 0.99);
  EXPECT_EQ(r1.lo, r2.lo);  // bit-identical: same seed, same stream, same arithmetic
  EXPECT_EQ(r1.hi, r2.hi);
  EXPECT_DOUBLE_EQ(r1.ratio, median(b) / median(a));
  RatioInterval other = bootstrapMedianRatio(a, b, 0.99, 2000, 12345);
  EXPECT_TRUE(other.lo != r1.lo || other.hi != r1.hi);
  EXPECT_DOUBLE_EQ(other.ratio, r1.ratio);
  EXPECT_LE(r1.lo, r1.ratio);
  EXPECT_GE(r1.hi, r1.ratio);
  // A narrower confidence gives a narrower interval from the same resamples.
  RatioInterval r90 = bootstrapMedianRatio(a, b, 0.90);
  EXPECT_GE(r90.lo, r1.lo);
  EXPECT_LE(r90.hi, r1.hi);
}

// Candidate = exactly twice the baseline: the ratio of medians is 2 and every resampled median
// lies between the samples' extremes, so the interval is within [2 * min / max, 2 * max / min].
TEST(CompareStats, BootstrapBracketsAScaledSample) {
  auto a = jittered(50, 1.0), b = jittered(50, 2.0);
  RatioInterval r = bootstrapMedianRatio(a, b, 0.99);
  EXPECT_DOUBLE_EQ(r.ratio, 2.0);
  EXPECT_LE(r.lo, 2.0);
  EXPECT_GE(r.hi, 2.0);
  EXPECT_GT(r.lo, 2.0 * 0.95 / 1.05);
  EXPECT_LT(r.hi, 2.0 * 1.05 / 0.95);
}

TEST(CompareStats, MedianIsPercentileFifty) {
  std::vector<double> odd = {5, 1, 4, 2, 3}, even = {4, 1, 3, 2};
  EXPECT_DOUBLE_EQ(median(odd), 3.0);
  EXPECT_DOUBLE_EQ(median(even), 2.5);
  EXPECT_DOUBLE_EQ(median(even), percentile(even, 50));
}

}  // namespace
}  // namespace lb
