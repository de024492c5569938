// The sweep's remaining-time estimate on synthetic sequences of measured costs: per
// scheme where known, the mean over the schemes run so far otherwise, and measurement frames
// counted at their own cost (they, not the timing frames, dominate a lavapipe sweep).
#include <gtest/gtest.h>

#include "sweep/progress.h"

namespace lb {
namespace {

CaseWork work(const std::string& scheme, int timing, int measured, bool overhead = true) {
  CaseWork w;
  w.scheme = scheme;
  w.timingFrames = timing;
  w.measuredFrames = measured;
  w.overhead = overhead;
  return w;
}

TEST(EtaEstimator, NothingMeasuredIsIncompleteNotZero) {
  EtaEstimator e;
  bool complete = true;
  EXPECT_EQ(e.remaining({work("uniform", 486, 13)}, complete), 0.0);
  EXPECT_FALSE(complete);  // unknown, said as such: never "~0s left"
  EXPECT_LT(e.timingCost("uniform"), 0);
  complete = false;
  EXPECT_EQ(e.remaining({}, complete), 0.0);
  EXPECT_TRUE(complete);  // nothing left is exactly nothing
}

// The sequence: uniform's timing frames took 19 s and its 13 measured frames 63 s. The old
// estimate (timing frames only) said ~84 s were left with three such cases to go; counting the
// measured frames at their cost gives the real 3 x 82 s.
TEST(EtaEstimator, MeasuredFramesAtTheirOwnCost) {
  EtaEstimator e;
  e.addTiming("uniform", 486, 19.0);
  e.addMeasured("uniform", 13, 63.0);
  e.addOverhead("uniform", 0.5);
  bool complete = false;
  double left = e.remaining({work("uniform", 486, 13), work("uniform", 486, 13), work("uniform", 486, 13)}, complete);
  EXPECT_TRUE(complete);
  EXPECT_NEAR(left, 3 * (19.0 + 63.0 + 0.5), 1e-9);
  // Timing known, measurement not yet: incomplete, and the figure covers the timing frames only.
  EtaEstimator t;
  t.addTiming("uniform", 486, 19.0);
  EXPECT_NEAR(t.remaining({work("uniform", 486, 13)}, complete), 19.0, 1e-9);
  EXPECT_FALSE(complete);
}

TEST(EtaEstimator, PerSchemeCostsWithTheMeanAsFallBack) {
  EtaEstimator e;
  // Two schemes with exact binary costs: a 0.25 s/timing frame, 4 s/measured frame; b 0.5 and 8.
  e.addTiming("a", 100, 25.0);
  e.addMeasured("a", 10, 40.0);
  e.addTiming("b", 100, 50.0);
  e.addMeasured("b", 10, 80.0);
  EXPECT_EQ(e.timingCost("a"), 0.25);
  EXPECT_EQ(e.measuredCost("b"), 8.0);
  // An unseen scheme: the mean over every frame so far (75 s / 200, 120 s / 20).
  EXPECT_EQ(e.timingCost("c"), 0.375);
  EXPECT_EQ(e.measuredCost("c"), 6.0);
  bool complete = false;
  double left = e.remaining({work("a", 8, 1, false), work("b", 8, 1, false), work("c", 8, 1, false)}, complete);
  EXPECT_TRUE(complete);
  EXPECT_EQ(left, (8 * 0.25 + 4.0) + (8 * 0.5 + 8.0) + (8 * 0.375 + 6.0));
  // Once c has run, its own cost replaces the mean.
  e.addTiming("c", 4, 4.0);
  e.addMeasured("c", 2, 1.0);
  EXPECT_EQ(e.timingCost("c"), 1.0);
  EXPECT_EQ(e.measuredCost("c"), 0.5);
  // Overheads are per case; a part with no work costs nothing even where its cost is unknown.
  EXPECT_EQ(e.remaining({work("c", 2, 0, false)}, complete), 2.0);
  EXPECT_TRUE(complete);
  EXPECT_EQ(e.remaining({work("c", 2, 0, true)}, complete), 2.0);
  EXPECT_FALSE(complete);
}

TEST(EtaEstimator, EmptyPartsAreNotSamples) {
  EtaEstimator e;
  e.addMeasured("a", 0, 5.0);  // a case without measurement passes teaches nothing about them
  EXPECT_LT(e.measuredCost("a"), 0);
  e.addTiming("a", 10, 1.0);
  e.addTiming("a", 30, 7.0);  // costs accumulate: 8 s / 40 frames
  EXPECT_EQ(e.timingCost("a"), 0.2);
}

// Ground truth is ray cast once per terrain, path and resolution, then cached: its cost is apart
// from the measured frames' (at 320x180: 21 s of the first case's 26 s of measurement passes), and
// only cases that make it pay it. Without that split, every later case looked 4x too expensive.
TEST(EtaEstimator, GroundTruthOnlyWhereItIsMade) {
  EtaEstimator e;
  e.addTiming("uniform", 161, 16.0);
  e.addMeasured("uniform", 5, 5.0);  // 26 s less the 21 s of ray casts
  e.addTruth(5, 21.0);
  e.addOverhead("uniform", 1.0);
  EXPECT_EQ(e.truthCost(), 4.2);
  CaseWork later = work("sphere", 161, 5);
  CaseWork first = later;
  first.truthFrames = 5;
  bool complete = false;
  EXPECT_NEAR(e.remaining({later}, complete), 16.0 + 5.0 + 1.0, 1e-9);
  EXPECT_TRUE(complete);
  EXPECT_NEAR(e.remaining({first}, complete), 16.0 + 5.0 + 1.0 + 21.0, 1e-9);
  EXPECT_TRUE(complete);
  EtaEstimator none;  // no ray cast timed yet: a case that makes some is incomplete
  none.addTiming("uniform", 10, 1.0);
  EXPECT_NEAR(none.remaining({work("uniform", 10, 0, false)}, complete), 1.0, 1e-12);
  EXPECT_TRUE(complete);
  CaseWork needsTruth = work("uniform", 10, 0, false);
  needsTruth.truthFrames = 1;
  none.remaining({needsTruth}, complete);
  EXPECT_FALSE(complete);
}

TEST(EtaEstimator, DurationText) {
  EXPECT_EQ(formatDuration(0), "0 s");
  EXPECT_EQ(formatDuration(84.4), "84 s");
  EXPECT_EQ(formatDuration(99.4), "99 s");
  EXPECT_EQ(formatDuration(246), "4 min 6 s");
  EXPECT_EQ(formatDuration(-3), "0 s");
}

}  // namespace
}  // namespace lb
