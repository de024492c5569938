#pragma once
// Matched comparisons: before a case runs, search its scheme's main parameter so that the case
// hits a triangle budget or a mean screen-space error on its path; schemes are then compared at
// equal cost or equal quality.
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

}  // namespace lb
