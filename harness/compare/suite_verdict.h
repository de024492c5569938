#pragma once
// The answer with its uncertainty: on each workload (a terrain and a camera path) every scheme's
// cost as a ratio to the workload's cheapest with a bootstrap interval, and across workloads each
// scheme's geometric-mean ratio with its interval, the workloads it wins and those it ties.
// Overlapping intervals are a tie, never a win (docs/results-format.md, verdict.json).
//
// Method (tests/test_suite_verdict.cpp checks it on synthetic timings with known answers): a
// repetition is the unit of evidence, as in `compare` (frames of one repetition share its clock
// and caches, and a path's frames are correlated in time, so they are not independent samples).
// A scheme's cost on a workload is the geometric mean over its repetitions of the repetition's
// mean GPU ms over the frames; the ratio to the workload's cheapest and its interval come from
// Welch's t on the logs of the repetition means (compare/significance.h roundTest). Across
// workloads, a scheme's geometric-mean ratio is exp of the mean of its log ratios, with a t
// interval whose variance sums the workloads' (independent runs) and whose degrees of freedom
// follow Welch-Satterthwaite. One repetition gives no interval: then nothing wins.
//
// Practical significance: a margin m (`lodbench verdict --margin`, default 0) makes a scheme tie
// the cheapest while its interval's lower bound is at most 1 + m, so a win needs every other
// scheme to be surely more than m slower. Repetitions on a GPU agree to 0.1 %, so without a margin
// a 1 % difference is a win; whether 1 % matters is the reader's call, and the margin states it.
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lb {

// One scheme's timings on one workload: GPU ms per repetition, per frame (the same frames in every
// repetition and for every scheme of the workload). `missing` says why there are none (failed,
// target unreachable); then `reps` is empty.
struct SchemeTimings {
  std::string scheme;
  std::vector<std::vector<double>> reps;
  std::string missing;
  std::string note;  // compared with a caveat (e.g. more accurate than the target at its coarsest)
  // Its cost is an upper bound: the coarsest configuration of its tuning space is already more
  // accurate than the target, so past that space it might cost less. It ties the cheapest however
  // far its interval lies above it: a win over it is not established.
  bool upperBound = false;
};

struct Workload {
  std::string id;  // terrain x path, as the run names them
  std::vector<SchemeTimings> schemes;
};

// NaN bounds: no interval (fewer than two repetitions on a side).
struct Interval {
  double value = 0, lo = 0, hi = 0;
};

struct WorkloadResult {
  std::string id;
  std::string cheapest;                   // by the point estimate
  std::map<std::string, double> costMs;   // point estimates
  std::map<std::string, Interval> ratio;  // to the cheapest (its own: exactly 1)
  std::map<std::string, std::string> missing;
  std::map<std::string, std::string> notes;  // SchemeTimings::note of the schemes compared
  std::vector<std::string> tied;             // the cheapest and every scheme whose interval reaches 1 (or has none)
  std::vector<std::string> bounded;          // of the tied, those only because their cost is an upper bound
  std::vector<std::string> noInterval;       // schemes (or the cheapest) with fewer than 2 repetitions
  bool verdict() const { return tied.size() == 1; }
};

struct SchemeResult {
  std::string scheme;
  Interval geomean;   // of its ratios over the workloads it ran
  int workloads = 0;  // with timings
  int wins = 0;       // cheapest, every other interval above 1
  int ties = 0;       // cheapest or within the interval of it, with another scheme
  std::vector<std::string> missingIn;
};

struct SuiteVerdict {
  double confidence = 0.95;
  double margin = 0;  // practical significance: ties within 1 + margin
  std::vector<WorkloadResult> workloads;
  std::vector<SchemeResult> schemes;  // by geometric-mean ratio, lowest first
};

// Throws std::invalid_argument when a scheme's repetitions differ in length or a workload's
// schemes have different frame counts.
SuiteVerdict suiteVerdict(const std::vector<Workload>& workloads, double confidence = 0.95, double margin = 0);

// verdict.json's content (docs/results-format.md).
nlohmann::json verdictJson(const SuiteVerdict& v);

struct RunData;
// A run's workloads: its cases grouped by terrain, path and resolution, in the run's order. A
// scheme is named by its scheme name, or its case label (scheme and listed parameters) where the
// workload holds several cases of it. Timings: each case's `gpu_ms` split into repetitions (the
// frame index starts again). Missing: a case not ok (its status and reason), or a matched case
// whose target was unreachable because even its finest setting errs more (the closest value tried
// and what it reached). A case more accurate than the target even at its coarsest setting meets
// the target: it is compared at that setting, with a note (its cost is then an upper bound).
std::vector<Workload> runWorkloads(const RunData& run);

// Writes RUN-DIR/verdict.json and returns the verdict (InputError for a directory that is not a run).
SuiteVerdict writeVerdict(const std::string& runDir, double confidence, double margin = 0);

// `lodbench verdict RUN-DIR...`: writes RUN-DIR/verdict.json for each run and prints its table;
// returns 0, or throws InputError for a directory that is not a run.
int verdictCommand(const std::vector<std::string>& runDirs, double confidence, double margin = 0);

}  // namespace lb
