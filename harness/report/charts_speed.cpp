// Speed-vs-accuracy charts (docs/design.md, Reports and regression checks): cost (GPU ms,
// triangles) against screen-space error, one point per case, each scheme's Pareto front per path
// as a line, and the error-bounded scheme's sweep over its bound (MainParamRole::ErrorBoundPx) as
// the dashed reference front. One panel per path and error kind, each with its own padded, round
// axis domain (charts_axes.cpp), so a paper can print any panel.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "report/charts.h"
#include "report/pareto.h"
#include "schemes/registry.h"

namespace lb {

using nlohmann::json;

namespace {

struct ErrorKind {
  const char* field;
  const char* label;  // panel title and data column "error"
  const char* axis;   // x-axis title: exactly what is plotted
};
constexpr ErrorKind kErrors[] = {{"err_mean_px", "mean error", "mean error (px), averaged over measured frames"},
                                 {"err_p95_px", "p95 error", "p95 error (px), averaged over measured frames"},
                                 {"flip_mean", "FLIP",
                                  "mean FLIP against the ray-cast truth (0..1), averaged over "
                                  "measured frames"}};

struct Cost {
  const char* id;
  const char* key;     // summary statistics object
  const char* field;   // data column
  const char* title;   // chart title
  const char* axis;    // y-axis title, with unit
  const char* better;  // the lower-left corner's annotation
};
constexpr Cost kCosts[] = {
    {"speed_gpu_ms", "gpu_ms", "gpu_ms", "GPU time vs screen-space error", "GPU ms/frame, median",
     "\u2199 better (faster, more accurate)"},
    {"speed_triangles", "triangles", "triangles", "Triangles vs screen-space error", "triangles/frame, median",
     "\u2199 better (fewer triangles, more accurate)"},
};

json fieldEquals(const char* field, const std::string& value) {
  return {{"field", field}, {"equal", value}};
}

// One panel: the rows of one path and error kind, on their own axes.
json panel(const ReportRun& run, const Cost& cost, const ErrorKind& err, const std::string& scenario,
           const AxisDomain& xd, const AxisDomain& yd, const std::string& boundScheme, bool hasBound,
           bool titleScenario) {
  json cell = {{"filter", {{"and", {fieldEquals("scenario", scenario), fieldEquals("error", err.label)}}}}};
  json x = positionEncoding("err_px", err.axis, xd);
  json y = positionEncoding(cost.field, cost.axis, yd);
  json color = schemeColor(run);
  json tooltip = json::array({{{"field", "case_id"}, {"title", "case"}},
                              {{"field", "params"}, {"title", "parameters"}},
                              {{"field", "err_px"}, {"title", std::string(err.label) + " (px)"}, {"format", ".3f"}},
                              {{"field", cost.field}, {"title", cost.axis}, {"format", ".4~g"}},
                              {{"field", "on_front"}, {"title", "on the scheme's Pareto front"}},
                              {{"field", "coverage_failed_frames"}, {"title", "frames missing terrain"}}});
  json layers = json::array();
  // Each scheme's Pareto front (the error-bounded scheme's own line is the dashed reference below).
  // Chart rows of that scheme carry "errbound": true.
  layers.push_back(
      {{"transform", {cell, {{"filter", "datum.on_front && !datum.errbound"}}}},
       {"mark", {{"type", "line"}, {"strokeWidth", 2}, {"opacity", 0.85}}},
       {"encoding",
        {{"x", x}, {"y", y}, {"color", color}, {"order", {{"field", "err_px"}, {"type", "quantitative"}}}}}});
  // The error-bounded scheme's sweep in bound order: the fewest triangles it needs for each error
  // level, the reference every scheme is read against. Only when present: an empty layer makes
  // Vega warn of infinite extents.
  if (hasBound)
    layers.push_back(
        {{"transform", {cell, {{"filter", "datum.errbound"}}}},
         {"mark",
          {{"type", "line"}, {"strokeDash", {6, 4}}, {"strokeWidth", 1.5}, {"color", schemeColour(boundScheme)}}},
         {"encoding", {{"x", x}, {"y", y}, {"order", {{"field", "sweep"}, {"type", "quantitative"}}}}}});
  layers.push_back(
      {{"transform", {cell}},
       {"mark", {{"type", "point"}, {"filled", true}, {"size", 70}, {"opacity", 0.9}}},
       {"encoding",
        {{"x", x}, {"y", y}, {"color", color}, {"shape", schemeShapeEncoding(run)}, {"tooltip", tooltip}}}});
  // Each point's parameter value beside it, so a printed chart says which setting is which.
  layers.push_back(
      {{"transform", {cell}},
       {"mark", {{"type", "text"}, {"align", "left"}, {"dx", 6}, {"dy", -5}, {"fontSize", 9}, {"color", "#333"}}},
       {"encoding", {{"x", x}, {"y", y}, {"text", {{"field", "value"}, {"type", "nominal"}}}}}});
  layers.push_back({{"data", {{"values", json::array({json::object()})}}},
                    {"mark",
                     {{"type", "text"},
                      {"text", cost.better},
                      {"align", "left"},
                      {"baseline", "bottom"},
                      {"dx", 6},
                      {"dy", -6},
                      {"fontSize", 11},
                      {"fontStyle", "italic"},
                      {"color", "#2e7d32"}}},
                    {"encoding", {{"x", {{"value", 0}}}, {"y", {{"value", "height"}}}}}});
  std::string title = titleScenario ? scenario + " \u00b7 " + err.label : std::string(err.label);
  return {{"title", title}, {"width", 460}, {"height", 320}, {"layer", layers}};
}

}  // namespace

std::vector<Chart> speedCharts(const ReportRun& run) {
  std::vector<Chart> charts;
  for (const Cost& cost : kCosts) {
    Chart chart;
    chart.id = chart.dataName = cost.id;
    chart.section = "speed";
    chart.title = cost.title;
    std::vector<std::string> unmeasured;
    std::set<std::string> uncovered;  // cases with coverage failures: their error means skip what was not drawn
    std::map<std::string, std::vector<double>> costsOf;                         // by scenario: one y axis per row
    std::map<std::pair<std::string, std::string>, std::vector<double>> errsOf;  // by scenario and error kind
    const Scheme* bounded = schemeWithRole(MainParamRole::ErrorBoundPx);
    const std::string boundScheme = bounded ? bounded->info().name : "",
                      boundParam = bounded ? bounded->info().mainParam : "";
    std::set<std::string> boundIn;  // scenarios with cases of the error-bounded scheme
    for (const ErrorKind& err : kErrors) {
      // Group cases by scheme and path: a front only compares settings of one scheme on one path.
      std::map<std::pair<std::string, std::string>, std::vector<const ReportCase*>> groups;
      for (auto& c : run.cases) {
        if (c.status != "ok" || !summaryStat(c.summary, cost.key, "median")) continue;
        if (!summaryStat(c.summary, err.field, "mean")) {
          if (&err == &kErrors[0]) unmeasured.push_back(c.label + " (" + c.scenario + ")");
          continue;
        }
        groups[{c.scheme, c.scenario}].push_back(&c);
      }
      for (auto& [key, cases] : groups) {
        std::vector<double> xs, costs;
        for (auto* c : cases) {
          xs.push_back(*summaryStat(c->summary, err.field, "mean"));
          costs.push_back(*summaryStat(c->summary, cost.key, "median"));
        }
        std::vector<bool> onFront(cases.size(), false);
        for (size_t i : paretoFront(xs, costs)) onFront[i] = true;
        for (size_t i = 0; i < cases.size(); ++i) {
          const ReportCase& c = *cases[i];
          auto cov = c.summary.find("coverage_failed_frames");
          const size_t failed = cov != c.summary.end() && cov->is_array() ? cov->size() : 0;
          if (failed) uncovered.insert(c.label + " (" + c.scenario + ")");
          bool isBound = bounded && c.scheme == boundScheme;
          auto bound = c.params.find(boundParam);
          double sweep = isBound && bound != c.params.end() && bound->is_number() ? bound->get<double>() : xs[i];
          chart.data.push_back({{"case_id", c.id},
                                {"scheme", c.scheme},
                                {"params", c.paramsLabel},
                                {"value", settingLabel(run, c)},
                                {"scenario", c.scenario},
                                {"error", err.label},
                                {"err_px", xs[i]},
                                {cost.field, costs[i]},
                                {"on_front", bool(onFront[i])},
                                {"errbound", isBound},
                                {"sweep", sweep},
                                {"coverage_failed_frames", failed}});
          costsOf[c.scenario].push_back(costs[i]);
          errsOf[{c.scenario, err.label}].push_back(xs[i]);
          if (isBound) boundIn.insert(c.scenario);
        }
      }
    }
    if (chart.data.empty()) {
      chart.note =
          std::string(cost.title) +
          ": left out, no case has both a cost and a screen-space error (err_mean_px, err_p95_px): the run had "
          "no measurement passes, or every case failed.";
      charts.push_back(std::move(chart));
      continue;
    }
    json rows = json::array();
    size_t shown = 0;
    for (auto& s : run.scenarios) shown += costsOf.count(s);
    for (auto& s : run.scenarios) {
      if (!costsOf.count(s)) continue;
      AxisDomain yd = niceDomain(costsOf[s]);
      json row = json::array();
      for (const ErrorKind& err : kErrors)
        if (errsOf.count({s, err.label}))
          row.push_back(panel(run, cost, err, s, niceDomain(errsOf[{s, err.label}]), yd, boundScheme,
                              boundIn.count(s) > 0, shown > 1));
      rows.push_back({{"hconcat", row}});
    }
    json subtitle =
        json::array({"one point per case, labelled with its parameter value; solid lines: each scheme's Pareto "
                     "front (no other setting of the scheme is both cheaper and more accurate)"});
    if (!boundIn.empty())
      subtitle.push_back("dashed: " + boundScheme + "'s sweep over " + boundParam + ", the reference front");
    chart.spec = {{"$schema", kVegaLiteSchema},
                  {"title", {{"text", cost.title}, {"subtitle", subtitle}}},
                  {"data", {{"url", "data/" + chart.dataName + ".json"}}},
                  {"vconcat", rows},
                  {"resolve", {{"scale", {{"color", "shared"}, {"shape", "shared"}}}}}};
    if (!unmeasured.empty()) {
      std::string list;
      for (auto& u : unmeasured) list += (list.empty() ? "" : ", ") + u;
      chart.caption = "Not shown (no error metrics): " + list + ".";
    }
    if (!uncovered.empty()) {
      std::string list;
      for (auto& u : uncovered) list += (list.empty() ? "" : ", ") + u;
      chart.caption += std::string(chart.caption.empty() ? "" : " ") +
                       "Accuracy failures plotted by their drawn pixels only (terrain missing or extra in some "
                       "measured frames, docs/results-format.md, Coverage): " +
                       list + ".";
    }
    charts.push_back(std::move(chart));
  }
  return charts;
}

}  // namespace lb
