#include "replay/case_search.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "replay/matched.h"
#include "results/write.h"

namespace lb {

using json = nlohmann::json;

// A matched search's record (docs/results-format.md, matched): every evaluation, those that
// could not run with their reason.
static json matchJson(const Config& config, const MatchResult& m) {
  json out = {
      {"metric", config.match.metric}, {"target", config.match.value}, {"param", m.param},        {"value", m.value},
      {"achieved", m.achieved},        {"evaluations", m.evaluations}, {"reachable", m.reachable}};
  json trials = json::array();
  for (const MatchTrial& t : m.trials) {
    json tj = {{"value", t.value}, {"achieved", std::isnan(t.achieved) ? json() : json(t.achieved)}};
    if (!t.reason.empty()) tj["reason"] = t.reason;
    trials.push_back(tj);
  }
  out["trials"] = trials;
  return out;
}

static CaseSearch runSearch(Context& ctx, const Scheme& scheme, const ParamValues& base, const Heightfield& terrain,
                            const CameraPath& path, const Config& config, const Case& c) {
  CaseSearch s;
  s.params = base;
  if (!c.tune.empty()) {
    // Each scheme at its best configuration: its tuning space, every configuration matched and
    // timed, the cheapest that reaches the target drawn (replay/matched.h tuneAndMatch).
    TuneResult t = tuneAndMatch(ctx, scheme, base, terrain, path, config, c);
    s.params = t.params;
    s.grid = t.grid;
    s.matched = matchJson(config, t.match);
    json trials = json::array();
    for (const TuneTrial& tr : t.trials)
      trials.push_back({{"settings", tr.settings},
                        {"match", matchJson(config, tr.match)},
                        {"cost_ms", std::isnan(tr.costMs) ? json() : json(tr.costMs)},
                        {"search_cost_ms", std::isnan(tr.searchCostMs) ? json() : json(tr.searchCostMs)},
                        {"retimed_ms", tr.retimedMs},
                        {"seconds", tr.seconds}});
    s.matched["tuned"] = {{"space", c.tune},
                          {"chosen", t.trials[size_t(t.chosen)].settings},
                          {"budget", t.budget},
                          {"evaluations", t.evaluations},
                          {"configurations", trials}};
  } else {
    MatchResult m = matchParameter(ctx, scheme, base, terrain, path, config, c);
    if (!m.param.empty()) s.params[m.param] = m.value;
    s.matched = matchJson(config, m);
  }
  return s;
}

// The checkpoint of the same case, or false: absent, unreadable, or another digest (the case's
// inputs changed, so its search must run again).
static bool readCheckpoint(const std::string& file, const Case& c, CaseSearch& s) {
  std::ifstream in(file);
  if (!in) return false;
  std::stringstream text;
  text << in.rdbuf();
  json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("digest", "") != c.digest || !j.contains("params") ||
      !j["params"].is_object() || !j.contains("matched") || !j["matched"].is_object())
    return false;
  s.params.clear();
  for (const auto& [k, v] : j["params"].items()) {
    if (!v.is_number()) return false;
    s.params[k] = v.get<double>();
  }
  s.grid = j.value("grid", 0);
  s.matched = j["matched"];
  return true;
}

CaseSearch searchCase(Context& ctx, const Scheme& scheme, const ParamValues& params, const Heightfield& terrain,
                      const CameraPath& path, const Config& config, const Case& c, const std::string& checkpoint) {
  CaseSearch s;
  if (!checkpoint.empty() && readCheckpoint(checkpoint, c, s)) {
    s.matched["checkpoint"] = "the search of an earlier invocation of this run, read back from its checkpoint";
    return s;
  }
  s = runSearch(ctx, scheme, params, terrain, path, config, c);
  if (!checkpoint.empty()) {
    json j = {{"case_id", c.id}, {"digest", c.digest}, {"params", s.params}, {"grid", s.grid}, {"matched", s.matched}};
    writeFileAtomic(checkpoint, j.dump(1));
  }
  return s;
}

}  // namespace lb
