// Small multiples: one panel per scheme (and path, where the run has several), wrapped into rows
// that fit the 1,400 px page with the legend above them. Within a panel the scheme's settings are
// told apart by a fixed ordinal colour ramp in ascending order of the setting, and the panel's
// title lists the values, so the parameter values are printed in every export.
#include <algorithm>
#include <map>
#include <set>

#include "report/charts.h"

namespace lb {

using nlohmann::json;

namespace {

// Light to dark: the first setting (smallest value) lightest. Eight steps; more settings repeat.
constexpr const char* kSettingRamp[] = {"#9ecae1", "#4292c6", "#08519c", "#fdae6b",
                                        "#e6550d", "#a63603", "#a1d99b", "#238b45"};

bool okCase(const ReportCase& c) {
  return c.status == "ok";
}

}  // namespace

std::string panelOf(const ReportRun& run, const ReportCase& c) {
  return run.scenarios.size() > 1 ? c.scheme + " \u00b7 " + c.scenario : c.scheme;
}

std::vector<std::string> panelOrder(const ReportRun& run) {
  std::vector<std::string> out;
  for (auto& s : run.schemes)
    for (auto& sc : run.scenarios)
      for (auto& c : run.cases)
        if (okCase(c) && c.scheme == s && c.scenario == sc) {
          out.push_back(panelOf(run, c));
          break;
        }
  return out;
}

int settingRank(const ReportRun& run, const ReportCase& c) {
  std::set<size_t> order;  // positions in run.paramLabels (natural order) of this scheme's settings
  for (auto& o : run.cases)
    if (okCase(o) && o.scheme == c.scheme)
      order.insert(
          size_t(std::find(run.paramLabels.begin(), run.paramLabels.end(), o.paramsLabel) - run.paramLabels.begin()));
  size_t mine =
      size_t(std::find(run.paramLabels.begin(), run.paramLabels.end(), c.paramsLabel) - run.paramLabels.begin());
  return 1 + int(std::distance(order.begin(), order.find(mine)));
}

std::string settingsTitle(const ReportRun& run, const std::string& scheme) {
  // name -> its values in the order of the cases' settings; parameters that do not vary are left out.
  std::vector<const ReportCase*> cases;
  for (auto& c : run.cases)
    if (okCase(c) && c.scheme == scheme) cases.push_back(&c);
  std::sort(cases.begin(), cases.end(), [&](auto* a, auto* b) { return settingRank(run, *a) < settingRank(run, *b); });
  std::vector<std::string> names;
  std::map<std::string, std::vector<std::string>> values;
  for (auto* c : cases)
    for (auto& [k, v] : c->params.items()) {
      if (!values.count(k)) names.push_back(k);
      std::string text = v.is_string() ? v.get<std::string>() : v.is_number() ? formatValue(v.get<double>()) : v.dump();
      if (std::find(values[k].begin(), values[k].end(), text) == values[k].end()) values[k].push_back(text);
    }
  std::string out;
  for (auto& k : names) {
    if (values[k].size() < 2) continue;
    std::string list;
    for (auto& v : values[k]) list += (list.empty() ? "" : " / ") + v;
    out += (out.empty() ? "" : ", ") + k + " " + list;
  }
  return out.empty() ? (cases.empty() ? "" : cases.front()->paramsLabel) : out;
}

std::string settingLabel(const ReportRun& run, const ReportCase& c) {
  std::set<std::string> varying;  // parameters whose value differs between the scheme's cases
  for (auto& o : run.cases)
    if (okCase(o) && o.scheme == c.scheme)
      for (auto& [k, v] : o.params.items())
        if (!c.params.contains(k) || c.params[k] != v) varying.insert(k);
  std::string out;
  for (auto& [k, v] : c.params.items())
    if (varying.count(k))
      out += (out.empty() ? "" : ", ") + (v.is_string()   ? v.get<std::string>()
                                          : v.is_number() ? formatValue(v.get<double>())
                                                          : v.dump());
  return out;
}

json settingColor(const ReportRun& run) {
  int most = 1;
  for (auto& c : run.cases)
    if (okCase(c)) most = std::max(most, settingRank(run, c));
  json domain = json::array(), range = json::array();
  for (int i = 1; i <= most; ++i) {
    domain.push_back(i);
    range.push_back(kSettingRamp[(i - 1) % std::size(kSettingRamp)]);
  }
  return {{"field", "setting"},
          {"type", "ordinal"},
          {"title", "setting, ascending (values in each panel's title)"},
          {"scale", {{"domain", domain}, {"range", range}}},
          {"legend", {{"orient", "top"}, {"direction", "horizontal"}, {"titleLimit", 400}}}};
}

json panelFacet(const ReportRun& run) {
  json titles = json::object();
  std::vector<std::string> order = panelOrder(run);
  // The panel's header: its scheme, path and the values of its settings in ramp order.
  std::string expr = "datum.value";
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    std::string scheme = it->substr(0, it->find(" \u00b7 "));
    std::string label = *it + ": " + settingsTitle(run, scheme);
    json quoted = label, key = *it;
    expr = "datum.value == " + key.dump() + " ? " + quoted.dump() + " : " + expr;
  }
  return {{"field", "panel"},
          {"type", "nominal"},
          {"title", nullptr},
          {"sort", order},
          {"header", {{"labelFontSize", 12}, {"labelLimit", 320}, {"labelExpr", expr}}}};
}

}  // namespace lb
