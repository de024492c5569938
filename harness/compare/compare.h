#pragma once
// lodbench compare (docs/design.md, Reports and regression checks): a candidate run against a baseline, case by case.
//  - exact: per-frame pipeline-statistics counters and deterministic measurements must be equal
//    (comparable only when both runs come from the same device and driver: otherwise the verdict
//    says loudly that they were not checked, and with requireExact it is an error);
//  - timing: the unit of evidence is the round (one run), not the frame: a t-test on the rounds'
//    log median GPU ms (>= minRounds per side); a regression is significant (p < alpha) AND
//    slower than 1 + threshold. With fewer rounds the ratio is reported without a verdict;
//  - accuracy: screen-space error, image and coverage metrics may not get worse beyond a tolerance
//    (coverage: plus kCoverageSlackPx); a metric the baseline has and the candidate lacks is a
//    regression; a candidate frame missing or adding terrain beyond metrics/coverage.h's tolerance
//    (summary coverage_failed_frames) is a regression whatever the baseline.
#include <string>
#include <vector>

#include "compare/run_data.h"

namespace lb {

// Coverage means (pixels) may rise by this much beyond the relative tolerance (see compare.cpp).
constexpr double kCoverageSlackPx = 1.0;

struct CompareOptions {
  double threshold = 0.10;       // timing: regression when ratio > 1 + threshold (and significant)
  double alpha = 0.01;           // significance level; the ratio interval is at 1 - alpha
  double errorTolerance = 0.02;  // accuracy: relative change in the worse direction allowed
  bool pairedRounds = false;     // round i of each side ran side by side (A/B mode)
  bool requireExact = false;     // counters that cannot be compared are an error (exit 2), not a pass
  int minRounds = 3;             // rounds per side needed for a timing verdict
};

struct ExactDiff {
  int frame = -1;                   // first differing frame (path frame index); -1 for a frame-set mismatch
  std::string field;                // e.g. "clip_invocations", "hist[3]", "frames"
  std::string baseline, candidate;  // the two values as JSON text
  int framesDiffering = 0;          // frames with any difference
  std::vector<std::string> fields;  // every field that differs somewhere
};

enum class TimingVerdict { NotChecked, Unchanged, Regression, Improvement };

struct TimingCheck {
  TimingVerdict verdict = TimingVerdict::NotChecked;
  std::string reason;                      // why no verdict
  double baselineMs = 0, candidateMs = 0;  // medians of the rounds' median GPU ms
  // Candidate / baseline: with a verdict, the geometric-mean ratio of the round medians with its
  // t interval at 1 - alpha; without, candidateMs / baselineMs (lo = hi = 0).
  double ratio = 0, lo = 0, hi = 0;
  double p = 1;                       // t-test on the rounds (1 without a verdict)
  int nBaseline = 0, nCandidate = 0;  // timing frames (for information: frames are not samples)
  int roundsBaseline = 0, roundsCandidate = 0;
  bool pairedRounds = false;
};

struct AccuracyCheck {
  std::string metric;
  bool higherIsWorse = true;
  double baseline = 0, candidate = 0;
  bool worse = false;
};

struct CaseComparison {
  std::string id;
  std::string baselineStatus, candidateStatus, statusNote;
  bool exactChecked = false;
  bool exactDiffers = false;
  ExactDiff exact;
  TimingCheck timing;
  std::vector<AccuracyCheck> accuracy;  // only metrics present in both
  // Draw paths that time their LOD apart (docs/draw-paths.md): the median of lod_ms, draw_ms and
  // lod_cpu_ms on each side (first round's summary), where both sides have it. Shown, not judged.
  struct Split {
    std::string key;
    double baseline = 0, candidate = 0;
  };
  std::vector<Split> split;
  std::vector<std::string> regressions;  // one line per reason this case regressed
  bool improved = false;
};

struct CompareReport {
  std::string baselineDir, candidateDir;
  nlohmann::json baselineContext, candidateContext;
  CompareOptions options;
  bool exactChecked = false;
  std::string exactSkipReason;          // why exact checks were skipped
  std::vector<std::string> notChecked;  // what this verdict did not check, said loudly in every output
  std::vector<std::string> onlyInBaseline, onlyInCandidate;
  std::vector<std::string> notes;     // run-level remarks (different devices, planted slowdown)
  std::vector<CaseComparison> cases;  // matched cases, sorted by id
  int regressions() const;            // cases with at least one regression
  int improvements() const;
  int exitCode() const { return regressions() > 0 || (options.requireExact && !onlyInBaseline.empty()) ? 1 : 0; }
};

// Throws InputError when options.requireExact and the counters cannot be compared.
CompareReport compareRuns(const RunData& baseline, const RunData& candidate, const CompareOptions& options);
const char* timingVerdictName(TimingVerdict v);

// How the ratio interval is computed, for the reports.
extern const char* const kTimingMethod;

}  // namespace lb
