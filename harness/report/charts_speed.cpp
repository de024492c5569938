// Speed-vs-accuracy charts (design section 8): cost (GPU ms, triangles) against screen-space
// error, one point per case, each scheme's Pareto front per path as a line.
#include <algorithm>
#include <cmath>
#include <map>

#include "report/charts.h"
#include "report/pareto.h"

namespace lb {

using nlohmann::json;

namespace {

constexpr double kLogSpan = 20;  // wider value ranges than this read better on a log axis

struct ErrorKind {
  const char* field;
  const char* label;
};
constexpr ErrorKind kErrors[] = {{"err_mean_px", "mean error"}, {"err_p95_px", "p95 error"}};

struct Cost {
  const char* id;
  const char* key;     // summary statistics object
  const char* field;   // data column
  const char* title;   // chart title
  const char* axis;    // y-axis title, with unit
  const char* better;  // the lower-left corner's annotation
};
constexpr Cost kCosts[] = {
    {"speed_gpu_ms", "gpu_ms", "gpu_ms", "GPU time vs screen-space error", "GPU time per frame (ms, median)",
     "\u2199 better (faster, more accurate)"},
    {"speed_triangles", "triangles", "triangles", "Triangles vs screen-space error", "triangles per frame (median)",
     "\u2199 better (fewer triangles, more accurate)"},
};

json speedSpec(const ReportRun& run, const Cost& cost, const std::string& yScale, const std::string& dataName,
               bool hasErrbound) {
  json x = {{"field", "err_px"},
            {"type", "quantitative"},
            {"title", "screen-space error (px, mean over measured frames)"},
            {"scale", {{"zero", false}}}};
  json y = {{"field", cost.field}, {"type", "quantitative"}, {"title", cost.axis}, {"scale", valueScale(yScale)}};
  json color = schemeColor(run);
  json shape = {
      {"field", "scheme"}, {"type", "nominal"}, {"title", "scheme"}, {"scale", {{"domain", chartSchemes(run)}}}};
  json tooltip = json::array({{{"field", "case_id"}, {"title", "case"}},
                              {{"field", "params"}, {"title", "parameters"}},
                              {{"field", "err_px"}, {"title", "error (px)"}, {"format", ".3f"}},
                              {{"field", cost.field}, {"title", cost.axis}, {"format", ".4~g"}},
                              {{"field", "on_front"}, {"title", "on the Pareto front"}}});
  json front = {
      {"transform", {{{"filter", "datum.on_front"}}}},
      {"mark", {{"type", "line"}, {"strokeWidth", 2}, {"opacity", 0.8}}},
      {"encoding", {{"x", x}, {"y", y}, {"color", color}, {"order", {{"field", "err_px"}, {"type", "quantitative"}}}}}};
  // errbound's sweep over max_error_px, all its cases on the path joined in error order: the
  // reference front (the fewest triangles errbound needs for each error level) every scheme is read against.
  json errboundFront = {
      {"transform", {{{"filter", "datum.errbound_front"}}}},
      {"mark", {{"type", "line"}, {"strokeDash", {6, 4}}, {"strokeWidth", 1.5}, {"color", "#222222"}}},
      {"encoding", {{"x", x}, {"y", y}, {"order", {{"field", "err_px"}, {"type", "quantitative"}}}}}};
  json points = {{"mark", {{"type", "point"}, {"filled", true}, {"size", 80}, {"opacity", 0.9}}},
                 {"encoding", {{"x", x}, {"y", y}, {"color", color}, {"shape", shape}, {"tooltip", tooltip}}}};
  // One row per facet cell carries corner=true, so the annotation is drawn once per cell.
  json better = {{"transform", {{{"filter", "datum.corner"}}}},
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
                 {"encoding", {{"x", {{"value", 0}}}, {"y", {{"value", "height"}}}}}};
  return {{"$schema", kVegaLiteSchema},
          {"title",
           {{"text", cost.title},
            {"subtitle",
             "one point per case; lines: each scheme's Pareto front (no other setting of the scheme "
             "is both cheaper and more accurate); dashed: errbound's sweep over max_error_px, the reference front"}}},
          {"data", {{"url", "data/" + dataName + ".json"}}},
          {"facet",
           {{"row", {{"field", "scenario"}, {"type", "nominal"}, {"title", "camera path"}, {"sort", run.scenarios}}},
            {"column",
             {{"field", "error"},
              {"type", "nominal"},
              {"title", nullptr},
              {"sort", {kErrors[0].label, kErrors[1].label}},
              {"header", {{"labelFontSize", 13}}}}}}},
          // The reference layer only when errbound has rows: an empty layer makes Vega warn of infinite extents.
          {"spec",
           {{"width", 320},
            {"height", 220},
            {"layer", hasErrbound ? json{front, points, better, errboundFront} : json{front, points, better}}}},
          {"resolve", {{"scale", {{"x", "independent"}, {"y", "independent"}}}}}};
}

}  // namespace

std::vector<std::string> chartSchemes(const ReportRun& run) {
  std::vector<std::string> out;
  for (auto& s : run.schemes)
    if (std::any_of(run.cases.begin(), run.cases.end(), [&](auto& c) { return c.scheme == s && c.status == "ok"; }))
      out.push_back(s);
  return out;
}

json schemeColor(const ReportRun& run) {
  return {{"field", "scheme"},
          {"type", "nominal"},
          {"title", "scheme"},
          {"scale", {{"domain", chartSchemes(run)}, {"scheme", "tableau10"}}}};
}

json valueScale(const std::string& type) {
  return type == "log" ? json{{"type", "log"}} : json{{"type", "linear"}, {"zero", false}};
}

std::string scaleTypeFor(const std::vector<double>& values) {
  double lo = INFINITY, hi = 0;
  for (double v : values) {
    if (v <= 0) return "linear";  // a log axis cannot show zero
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return !values.empty() && hi / lo > kLogSpan ? "log" : "linear";
}

std::vector<Chart> speedCharts(const ReportRun& run) {
  std::vector<Chart> charts;
  for (const Cost& cost : kCosts) {
    Chart chart;
    chart.id = chart.dataName = cost.id;
    chart.section = "speed";
    chart.title = cost.title;
    std::vector<std::string> unmeasured;
    std::vector<double> ys;
    std::map<std::string, bool> cornerDone;
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
          std::string cell = key.second + "|" + err.label;
          bool corner = !cornerDone[cell];
          cornerDone[cell] = true;
          chart.data.push_back({{"case_id", cases[i]->id},
                                {"scheme", cases[i]->scheme},
                                {"params", cases[i]->paramsLabel},
                                {"scenario", cases[i]->scenario},
                                {"error", err.label},
                                {"err_px", xs[i]},
                                {cost.field, costs[i]},
                                {"on_front", bool(onFront[i])},
                                {"errbound_front", cases[i]->scheme == "errbound"},
                                {"corner", corner}});
          ys.push_back(costs[i]);
        }
      }
    }
    if (chart.data.empty()) {
      chart.note =
          std::string(cost.title) +
          ": left out, no case has both a cost and a screen-space error (err_mean_px, err_p95_px): the run had "
          "no measurement passes, or every case failed.";
    } else {
      bool hasErrbound = std::any_of(chart.data.begin(), chart.data.end(), [](const json& r) { return r["errbound_front"] == true; });
      chart.spec = speedSpec(run, cost, scaleTypeFor(ys), chart.dataName, hasErrbound);
      if (!unmeasured.empty()) {
        std::string list;
        for (auto& u : unmeasured) list += (list.empty() ? "" : ", ") + u;
        chart.caption = "Not shown (no error metrics): " + list + ".";
      }
    }
    charts.push_back(std::move(chart));
  }
  return charts;
}

}  // namespace lb
