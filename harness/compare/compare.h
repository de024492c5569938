#pragma once
// lodbench compare (design section 8): a candidate run against a baseline, case by case.
//  - exact: per-frame pipeline-statistics counters and deterministic measurements must be equal
//    (only when both runs come from the same device and driver);
//  - timing: ratio of median GPU ms with a bootstrap interval, two-sided Mann-Whitney U test;
//    a regression is significant (p < alpha) AND slower than 1 + threshold (with several rounds,
//    as in A/B mode, the ratio of the rounds' medians must be beyond the threshold too);
//  - accuracy: screen-space error and image metrics may not get worse beyond a tolerance.
#include <string>
#include <vector>

#include "compare/run_data.h"

namespace lb {

struct CompareOptions {
  double threshold = 0.10;       // timing: regression when ratio > 1 + threshold (and significant)
  double alpha = 0.01;           // significance level; the ratio interval is at 1 - alpha
  double errorTolerance = 0.02;  // accuracy: relative change in the worse direction allowed
  bool pairedRounds = false;     // round i of each side ran side by side (A/B mode)
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
  std::string reason;                      // why not checked
  double baselineMs = 0, candidateMs = 0;  // medians of the pooled per-frame GPU ms
  double ratio = 0, lo = 0, hi = 0;        // candidate / baseline with its interval
  double p = 1;
  int nBaseline = 0, nCandidate = 0;
  // With several rounds on a side (0 otherwise): paired (A/B mode) = median over i of
  // candidate_i / baseline_i of the rounds' medians; else median of the candidate's round medians
  // over the median of the baseline's.
  double roundRatio = 0;
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
  std::vector<AccuracyCheck> accuracy;   // only metrics present in both
  std::vector<std::string> regressions;  // one line per reason this case regressed
  bool improved = false;
};

struct CompareReport {
  std::string baselineDir, candidateDir;
  nlohmann::json baselineContext, candidateContext;
  CompareOptions options;
  bool exactChecked = false;
  std::string exactSkipReason;  // why exact checks were skipped
  std::vector<std::string> onlyInBaseline, onlyInCandidate;
  std::vector<std::string> notes;     // run-level remarks (different devices, planted slowdown)
  std::vector<CaseComparison> cases;  // matched cases, sorted by id
  int regressions() const;            // cases with at least one regression
  int improvements() const;
  int exitCode() const { return regressions() > 0 ? 1 : 0; }
};

CompareReport compareRuns(const RunData& baseline, const RunData& candidate, const CompareOptions& options);
const char* timingVerdictName(TimingVerdict v);

// How the ratio interval is computed, for the reports.
extern const char* const kTimingMethod;

}  // namespace lb
