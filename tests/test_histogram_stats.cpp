// Histogram-derived statistics, checked against values computed by hand from the bin edges.
#include <gtest/gtest.h>

#include <cmath>

#include "metrics/histogram_stats.h"
#include "render/renderer.h"

using namespace lb;

namespace {

// 10 in [1/4,1/2), 30 in [1,2), 40 in [4,8), 20 in >= 1024; 100 binned, plus some not binned.
TriangleHistogram sampleHistogram() {
  TriangleHistogram h;
  h.bins[2] = 10;
  h.bins[4] = 30;
  h.bins[6] = 40;
  h.bins[14] = 20;
  h.offscreen = 7;
  h.backfacing = 5;
  return h;
}

}  // namespace

TEST(HistogramStats, FractionUnderOnePixelIsExact) {
  HistogramStats s = histogramStats(sampleHistogram());
  EXPECT_EQ(s.binned, 100u) << "offscreen and backfacing triangles are not binned";
  EXPECT_DOUBLE_EQ(s.fracUnder1px, 0.10);  // only the 10 in [1/4,1/2) are under 1 px
}

TEST(HistogramStats, MedianInterpolatesLogLinearlyInsideTheMedianBin) {
  // Half of 100 is 50; 40 lie below [4,8), so the median is 10/40 of the way through it in log2.
  EXPECT_DOUBLE_EQ(histogramStats(sampleHistogram()).medianArea, 4.0 * std::pow(2.0, 0.25));
  TriangleHistogram tiny;
  tiny.bins[0] = 8;  // bin 0 is taken as [1/16, 1/8): its middle in log2 is 2^-3.5
  EXPECT_DOUBLE_EQ(histogramStats(tiny).medianArea, std::pow(2.0, -3.5));
  TriangleHistogram huge;
  huge.bins[14] = 3;
  huge.bins[13] = 1;  // median: (2 - 1) / 3 through bin 14, taken as [1024, 2048)
  EXPECT_DOUBLE_EQ(histogramStats(huge).medianArea, 1024.0 * std::pow(2.0, 1.0 / 3.0));
}

TEST(HistogramStats, MeanIsExactWithAnAreaSumAndEstimatedWithout) {
  HistogramStats exact = histogramStats(sampleHistogram(), NAN, 12345.0);
  EXPECT_TRUE(exact.meanExact);
  EXPECT_DOUBLE_EQ(exact.meanArea, 123.45);
  // Geometric centres lo * sqrt(2): (10/4 + 30 * 1 + 40 * 4 + 20 * 1024) * sqrt(2) / 100.
  HistogramStats estimate = histogramStats(sampleHistogram());
  EXPECT_FALSE(estimate.meanExact);
  EXPECT_DOUBLE_EQ(estimate.meanArea, 20672.5 * std::sqrt(2.0) / 100.0);
}

TEST(HistogramStats, NearTargetIsExactOnBinEdgesAndLogUniformInside) {
  // Target 2: [1, 4] is exactly bins [1,2) and [2,4): 30 of 100.
  EXPECT_DOUBLE_EQ(histogramStats(sampleHistogram(), 2.0).fracNearTarget, 0.30);
  // Target 3: [1.5, 6] takes 1 - log2(1.5) of [1,2) and log2(6) - 2 = log2(1.5) of [4,8):
  // (30 (1 - log2 1.5) + 40 log2 1.5) / 100 = (30 + 10 log2 1.5) / 100.
  EXPECT_NEAR(histogramStats(sampleHistogram(), 3.0).fracNearTarget, (30.0 + 10.0 * std::log2(1.5)) / 100.0, 1e-12);
  // Target 1024: [512, 2048] covers [512,1024) (empty) and bin 14 taken as [1024, 2048): 20 of 100.
  EXPECT_DOUBLE_EQ(histogramStats(sampleHistogram(), 1024.0).fracNearTarget, 0.20);
  EXPECT_TRUE(std::isnan(histogramStats(sampleHistogram()).fracNearTarget)) << "no target";
  EXPECT_TRUE(std::isnan(histogramStats(sampleHistogram(), 0.0).fracNearTarget)) << "no target";
}

TEST(HistogramStats, EmptyHistogramGivesNaN) {
  TriangleHistogram h;
  h.offscreen = 4;
  HistogramStats s = histogramStats(h, 2.0, 0.0);
  EXPECT_EQ(s.binned, 0u);
  EXPECT_TRUE(std::isnan(s.fracUnder1px));
  EXPECT_TRUE(std::isnan(s.medianArea));
  EXPECT_TRUE(std::isnan(s.meanArea));
  EXPECT_TRUE(std::isnan(s.fracNearTarget));
}
