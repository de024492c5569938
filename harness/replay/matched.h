#pragma once
// Matched comparisons: before a case runs, search its scheme's main parameter so that the case
// hits a triangle budget or a mean screen-space error on its path; schemes are then compared at
// equal cost or equal quality.
#include <map>
#include <string>
#include <vector>

#include "config/match_spec.h"
#include "render/scheme.h"

namespace lb {

struct Context;
struct Config;
struct Case;
struct Heightfield;
struct CameraPath;

// One evaluation of the search: the value tried, the metric it reached (NaN when it could not run)
// and why it could not.
struct MatchTrial {
  double value = 0;
  double achieved = 0;
  std::string reason;
};

struct MatchResult {
  std::string param;    // the parameter searched ("" when the scheme has none)
  double value = 0;     // chosen value
  double achieved = 0;  // the metric at that value
  int evaluations = 0;
  bool reachable = true;           // false when the target lies outside the parameter's range
  std::vector<MatchTrial> trials;  // every evaluation in order, those that could not run included
};

// The parameter a match searches is the scheme's SchemeInfo::mainParam; "" = none, nothing is searched.
MatchResult matchParameter(Context& ctx, const Scheme& scheme, const ParamValues& base, const Heightfield& terrain,
                           const CameraPath& path, const Config& config, const Case& c);

// One configuration of a tuned search: its settings ("grid" and parameters), the main
// parameter's search there, and the GPU ms a frame costs at the value found (NaN: not timed, the
// search could not run).
// costMs is what the choice reads: for a configuration that meets the target, when two or more
// do, the median of its re-timed rounds (retimedMs); searchCostMs is the first timing, right after
// its search.
struct TuneTrial {
  std::map<std::string, double> settings;
  MatchResult match;
  double costMs = 0;
  double searchCostMs = 0;
  std::vector<double> retimedMs;  // empty: not re-timed
  double seconds = 0;             // wall time of its search and timing, renderer set-up included
};

struct TuneResult {
  ParamValues params;  // the chosen configuration's parameters, the main one at its matched value
  int grid = 0;        // its patch grid
  MatchResult match;   // its search
  std::vector<TuneTrial> trials;
  int chosen = -1;      // index into trials
  int evaluations = 0;  // over every configuration
  int budget = 0;
};

// Whether a search meets its target: reached it, or (an error target) stayed more accurate than it
// even at the coarsest setting.
bool meetsTarget(const MatchResult& m, const MatchSpec& spec);

// The configuration a tuned search draws (index into `trials`; -1 when none was timed): the cheapest
// of those that meet the target, else the one whose metric came closest to it. A configuration too
// accurate at its coarsest meets an error target: choosing by closeness there would pick a coarser
// grid that misses the target over a finer one that meets it.
int chooseConfiguration(const std::vector<TuneTrial>& trials, const MatchSpec& spec);

// The tuned search (each scheme at its best configuration): for every configuration of the
// case's tuning space (Case::tune: the cartesian product of its settings), the main parameter's
// matched search with min(iterations, max(2, budget / K - 2)) steps, then the mean GPU ms of the
// match's frames at the value found. The cheapest configuration that meets the target wins
// (chooseConfiguration); if none does, the one whose metric is closest to it (its match says
// unreachable). A configuration
// that cannot run is recorded and skipped; throws only when none runs.
TuneResult tuneAndMatch(Context& ctx, const Scheme& scheme, const ParamValues& base, const Heightfield& terrain,
                        const CameraPath& path, const Config& config, const Case& c);

}  // namespace lb
