#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "stats.h"

namespace lb {
namespace {

std::vector<double> oneToHundred() {
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  return v;
}

// Expected values are what numpy.percentile(..., method="linear") returns.
TEST(Stats, PercentileOneToHundred) {
  const std::vector<double> v = oneToHundred();
  EXPECT_DOUBLE_EQ(percentile(v, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(v, 100), 100.0);
  EXPECT_DOUBLE_EQ(percentile(v, 50), 50.5);
  EXPECT_DOUBLE_EQ(percentile(v, 5), 5.95);
  EXPECT_DOUBLE_EQ(percentile(v, 95), 95.05);
  EXPECT_DOUBLE_EQ(percentile(v, 99), 99.01);
  EXPECT_DOUBLE_EQ(percentile(v, 25), 25.75);
}

TEST(Stats, PercentileEmptyIsZero) {
  EXPECT_EQ(percentile({}, 50), 0.0);
  EXPECT_EQ(percentile({}, 99), 0.0);
}

TEST(Stats, PercentileSingleElement) {
  for (double q : {0.0, 5.0, 50.0, 99.0, 100.0}) EXPECT_EQ(percentile({7.25}, q), 7.25);
}

TEST(Stats, PercentileTwoElements) {
  EXPECT_DOUBLE_EQ(percentile({10, 20}, 0), 10.0);
  EXPECT_DOUBLE_EQ(percentile({10, 20}, 50), 15.0);
  EXPECT_DOUBLE_EQ(percentile({10, 20}, 95), 19.5);
  EXPECT_DOUBLE_EQ(percentile({10, 20}, 100), 20.0);
}

TEST(Stats, PercentileUnsortedInput) {
  const std::vector<double> v = {9, 1, 5, 3, 7};
  EXPECT_DOUBLE_EQ(percentile(v, 50), 5.0);
  EXPECT_DOUBLE_EQ(percentile(v, 25), 3.0);
  EXPECT_DOUBLE_EQ(percentile(v, 90), 8.2);
  EXPECT_DOUBLE_EQ(percentile({4, 1, 3, 2}, 50), 2.5);
}

TEST(Stats, PercentileClampsQ) {
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3}, -10), 1.0);
  EXPECT_DOUBLE_EQ(percentile({1, 2, 3}, 250), 3.0);
}

TEST(Stats, SummarizeOneToHundred) {
  const Summary s = summarize(oneToHundred());
  EXPECT_EQ(s.count, 100);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
  EXPECT_DOUBLE_EQ(s.median, 50.5);
  EXPECT_DOUBLE_EQ(s.p5, 5.95);
  EXPECT_DOUBLE_EQ(s.p95, 95.05);
  EXPECT_DOUBLE_EQ(s.p99, 99.01);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 100.0);
  EXPECT_DOUBLE_EQ(s.stddev, std::sqrt((100.0 * 100.0 - 1.0) / 12.0));  // population sd of 1..n
}

TEST(Stats, SummarizeEmpty) {
  const Summary s = summarize({});
  EXPECT_EQ(s.count, 0);
  EXPECT_EQ(s.mean, 0.0);
  EXPECT_EQ(s.median, 0.0);
  EXPECT_EQ(s.p99, 0.0);
  EXPECT_EQ(s.min, 0.0);
  EXPECT_EQ(s.max, 0.0);
  EXPECT_EQ(s.stddev, 0.0);
}

TEST(Stats, SummarizeSingleAndTwo) {
  const Summary one = summarize({3.5});
  EXPECT_EQ(one.count, 1);
  EXPECT_EQ(one.mean, 3.5);
  EXPECT_EQ(one.median, 3.5);
  EXPECT_EQ(one.p5, 3.5);
  EXPECT_EQ(one.p99, 3.5);
  EXPECT_EQ(one.stddev, 0.0);

  const Summary two = summarize({4, 2});
  EXPECT_EQ(two.count, 2);
  EXPECT_DOUBLE_EQ(two.mean, 3.0);
  EXPECT_DOUBLE_EQ(two.median, 3.0);
  EXPECT_DOUBLE_EQ(two.p5, 2.1);
  EXPECT_DOUBLE_EQ(two.p95, 3.9);
  EXPECT_EQ(two.min, 2.0);
  EXPECT_EQ(two.max, 4.0);
  EXPECT_DOUBLE_EQ(two.stddev, 1.0);
}

TEST(Stats, SummarizeUnsortedKnownSpread) {
  // Classic example: population standard deviation exactly 2.
  const Summary s = summarize({9, 2, 5, 4, 4, 7, 5, 4});
  EXPECT_EQ(s.count, 8);
  EXPECT_DOUBLE_EQ(s.mean, 5.0);
  EXPECT_DOUBLE_EQ(s.stddev, 2.0);
  EXPECT_DOUBLE_EQ(s.median, 4.5);
  EXPECT_EQ(s.min, 2.0);
  EXPECT_EQ(s.max, 9.0);
}

TEST(Stats, StddevStableForLargeNearlyEqualValues) {
  // Frame times in ns are ~1.6e7 with small jitter; naive sum of squares would lose it.
  const Summary s = summarize({16666666.0 + 1, 16666666.0 - 1, 16666666.0 + 1, 16666666.0 - 1});
  EXPECT_DOUBLE_EQ(s.stddev, 1.0);
}

TEST(Stats, NanDoesNotCrashSort) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(percentile({3, nan, 1, 2}, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile({3, nan, 1, 2}, 50), 2.5);
}

}  // namespace
}  // namespace lb
