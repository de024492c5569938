// Scale-study charts: how GPU time (median and p95) and triangles grow with the patch
// grid, the resolution and each scheme's swept parameter (errbound: max_error_px). A chart is made
// only when the run varies its variable with everything else held: cases that differ in that
// variable alone form one line; cases whose line would be a single point are left out.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <set>

#include "report/charts.h"

namespace lb {

using nlohmann::json;

namespace {

struct Metric {
  const char* field;  // data column
  const char* key;    // summary statistics object
  const char* stat;
  const char* title;  // panel title
  const char* axis;   // y-axis title, with unit
};
constexpr Metric kMetrics[] = {
    {"gpu_median", "gpu_ms", "median", "GPU time, median", "GPU ms/frame, median"},
    {"gpu_p95", "gpu_ms", "p95", "GPU time, p95", "GPU ms/frame, p95"},
    {"triangles", "triangles", "median", "triangles, median", "triangles/frame, median"},
};

std::string resolutionOf(const ReportCase& c) {
  return std::to_string(c.width) + "x" + std::to_string(c.height);
}
std::string placeOf(const ReportCase& c) {  // the camera path's stem
  if (c.path.empty()) return "(no path)";
  std::string name = c.path.substr(c.path.find_last_of('/') + 1);
  return name.substr(0, name.rfind('.'));
}

// What a chart varies: its x value and label for a case, and the key of everything else held.
struct Variable {
  std::string id, title, axis, what;
  bool perRow;  // the x axis differs per panel row (parameters of different schemes)
};

struct Point {
  const ReportCase* c;
  double x;
  std::string row;      // panel row
  std::string series;   // one line
  std::string variant;  // the line's legend entry (what else differs between lines of one colour)
};

std::string numberLabel(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Keeps points whose series has at least two x values; empty when none.
std::vector<Point> varying(std::vector<Point> points) {
  std::map<std::string, std::set<double>> xs;
  for (auto& p : points) xs[p.series].insert(p.x);
  points.erase(std::remove_if(points.begin(), points.end(), [&](const Point& p) { return xs[p.series].size() < 2; }),
               points.end());
  return points;
}

// Each scheme's own parameter: small multiples, one panel per scheme and parameter wrapped
// kPanelColumns to a row, one grid for GPU time (median solid, p95 dashed) and one for triangles,
// each on one shared y axis so panels compare; the x axis is the panel's parameter.
json perSchemeGrids(const ReportRun& run, const Variable& v, const std::vector<std::string>& rows,
                    std::map<std::string, std::vector<double>>& xOf,
                    std::map<std::pair<std::string, std::string>, std::vector<double>>& yOf,
                    const std::function<AxisDomain(const std::vector<double>&)>& xDomain) {
  struct Grid {
    const char* title;
    std::vector<const Metric*> lines;  // first solid, second dashed
  };
  const Grid grids[] = {{"GPU time (ms/frame): median solid, p95 dashed", {&kMetrics[0], &kMetrics[1]}},
                        {"triangles/frame, median", {&kMetrics[2]}}};
  json out = json::array();
  for (const Grid& g : grids) {
    std::vector<double> all;
    for (auto& r : rows)
      for (auto* m : g.lines) all.insert(all.end(), yOf[{r, m->field}].begin(), yOf[{r, m->field}].end());
    if (all.empty()) continue;
    AxisDomain yd = niceDomain(all);
    json panels = json::array();
    for (auto& r : rows) {
      json x = positionEncoding("x", r.substr(0, r.find(" (")), xDomain(xOf[r]));
      json layers = json::array();
      for (size_t i = 0; i < g.lines.size(); ++i) {
        const Metric& m = *g.lines[i];
        // One title for the layers (Vega-Lite joins differing ones with commas).
        json y = positionEncoding(m.field, g.lines.size() > 1 ? "GPU ms/frame" : "triangles/frame", yd);
        json line = {{"type", "line"}, {"strokeWidth", 1.75}};
        if (i > 0) line["strokeDash"] = {5, 3};
        json tip = json::array({{{"field", "case_id"}, {"title", "case"}},
                                {{"field", "params"}, {"title", "parameters"}},
                                {{"field", m.field}, {"title", m.axis}, {"format", ".4~g"}}});
        json enc = {
            {"x", x}, {"y", y}, {"color", schemeColor(run)}, {"detail", {{"field", "series"}, {"type", "nominal"}}}};
        layers.push_back(
            {{"transform", {{{"filter", {{"valid", true}, {"field", m.field}}}}}}, {"mark", line}, {"encoding", enc}});
        json pts = enc;
        pts.erase("detail");
        pts["shape"] = schemeShapeEncoding(run);
        pts["tooltip"] = tip;
        layers.push_back({{"transform", {{{"filter", {{"valid", true}, {"field", m.field}}}}}},
                          {"mark", {{"type", "point"}, {"filled", true}, {"size", 45}}},
                          {"encoding", pts}});
      }
      panels.push_back({{"title", {{"text", r}, {"fontSize", 12}}},
                        {"width", kPanelWidth - 20},
                        {"height", 130},
                        {"transform", {{{"filter", {{"field", "row"}, {"equal", r}}}}}},
                        {"layer", layers}});
    }
    out.push_back({{"title", g.title}, {"columns", kPanelColumns}, {"concat", panels}});
  }
  return {{"$schema", kVegaLiteSchema},
          {"title", {{"text", v.title}, {"subtitle", v.what}}},
          {"data", {{"url", "data/" + v.id + ".json"}}},
          {"vconcat", out},
          {"config", {{"legend", {{"orient", "top"}, {"direction", "horizontal"}, {"columns", 7}}}}},
          {"resolve", {{"scale", {{"color", "shared"}, {"shape", "shared"}}}}}};
}

Chart build(const ReportRun& run, const Variable& v, const std::vector<Point>& points,
            const std::function<AxisDomain(const std::vector<double>&)>& xDomain) {
  Chart chart;
  chart.id = chart.dataName = v.id;
  chart.section = "scale";
  chart.title = v.title;
  std::vector<std::string> rows, variants;
  std::map<std::string, std::vector<double>> xOf;
  std::map<std::pair<std::string, std::string>, std::vector<double>> yOf;
  for (auto& p : points) {
    if (std::find(rows.begin(), rows.end(), p.row) == rows.end()) rows.push_back(p.row);
    if (std::find(variants.begin(), variants.end(), p.variant) == variants.end()) variants.push_back(p.variant);
    json row = {{"case_id", p.c->id},
                {"scheme", p.c->scheme},
                {"params", p.c->paramsLabel},
                {"row", p.row},
                {"series", p.series},
                {"variant", p.variant},
                {"x", p.x},
                {"resolution", resolutionOf(*p.c)},
                {"grid", p.c->grid}};
    for (const Metric& m : kMetrics) {
      auto val = summaryStat(p.c->summary, m.key, m.stat);
      row[m.field] = val ? json(*val) : json(nullptr);
      if (val) yOf[{p.row, m.field}].push_back(*val);
    }
    xOf[v.perRow ? p.row : ""].push_back(p.x);
    chart.data.push_back(row);
  }
  if (v.perRow) {
    chart.spec = perSchemeGrids(run, v, rows, xOf, yOf, xDomain);
    return chart;
  }
  json vrows = json::array();
  for (auto& r : rows) {
    AxisDomain xd = xDomain(xOf[v.perRow ? r : ""]);
    json x = positionEncoding("x", v.perRow ? r : v.axis, xd);  // per row: the parameter's name
    json panels = json::array();
    for (const Metric& m : kMetrics) {
      if (!yOf.count({r, m.field})) continue;
      json y = positionEncoding(m.field, m.axis, niceDomain(yOf[{r, m.field}]));
      json enc = {
          {"x", x}, {"y", y}, {"color", schemeColor(run)}, {"detail", {{"field", "series"}, {"type", "nominal"}}}};
      if (variants.size() > 1)
        enc["strokeDash"] = {{"field", "variant"},
                             {"type", "nominal"},
                             {"title", "line"},
                             {"sort", variants},
                             {"legend", {{"labelLimit", 400}, {"symbolStrokeColor", "#444"}}}};
      json pointsEnc = {{"x", x},
                        {"y", y},
                        {"color", schemeColor(run)},
                        {"shape", schemeShapeEncoding(run)},
                        {"tooltip", json::array({{{"field", "case_id"}, {"title", "case"}},
                                                 {{"field", m.field}, {"title", m.axis}, {"format", ".4~g"}}})}};
      json filter = {{"filter", {{"and", {{{"field", "row"}, {"equal", r}}, {{"field", m.field}, {"valid", true}}}}}}};
      panels.push_back({{"title", rows.size() > 1 ? r + " \u00b7 " + m.title : std::string(m.title)},
                        {"width", 260},
                        {"height", 240},
                        {"transform", {filter}},
                        {"layer",
                         {{{"mark", {{"type", "line"}, {"strokeWidth", 1.75}}}, {"encoding", enc}},
                          {{"mark", {{"type", "point"}, {"filled", true}, {"size", 60}}}, {"encoding", pointsEnc}}}}});
    }
    vrows.push_back({{"hconcat", panels}});
  }
  chart.spec = {{"$schema", kVegaLiteSchema},
                {"title", {{"text", v.title}, {"subtitle", v.what}}},
                {"data", {{"url", "data/" + chart.dataName + ".json"}}},
                {"vconcat", vrows},
                {"resolve", {{"scale", {{"color", "shared"}, {"shape", "shared"}, {"strokeDash", "shared"}}}}}};
  return chart;
}

std::vector<const ReportCase*> timed(const ReportRun& run) {
  std::vector<const ReportCase*> out;
  for (auto& c : run.cases)
    if (c.status == "ok" && summaryStat(c.summary, "gpu_ms", "median")) out.push_back(&c);
  return out;
}

}  // namespace

std::vector<Chart> scaleCharts(const ReportRun& run) {
  std::vector<Chart> charts;
  std::vector<const ReportCase*> cases = timed(run);
  std::set<int> grids;
  std::set<std::string> resolutions;
  for (auto* c : cases) grids.insert(c->grid), resolutions.insert(resolutionOf(*c));

  // Against the grid: one line per scheme, parameters, path, terrain and resolution.
  std::vector<Point> points;
  for (auto* c : cases) {
    if (c->grid <= 0) continue;
    std::string held = placeOf(*c) + (c->terrain.empty() ? "" : " / " + c->terrain);
    std::string variant = c->paramsLabel + (resolutions.size() > 1 ? ", " + resolutionOf(*c) : "");
    points.push_back({c, double(c->grid), held, c->scheme + "|" + variant + "|" + held, c->scheme + " " + variant});
  }
  if (auto p = varying(points); !p.empty())
    charts.push_back(build(run,
                           {"scale_grid", "Cost vs patch grid", "patch grid, patches per side",
                            "one line per scheme and setting, everything but the grid held; log2 axis", false},
                           p, log2Domain));

  // Against the resolution (pixels per frame): ticks named by the resolutions themselves.
  points.clear();
  std::map<double, std::string> names;
  for (auto* c : cases) {
    if (c->width <= 0 || c->height <= 0) continue;
    double px = double(c->width) * c->height;
    names[px] = resolutionOf(*c);
    std::string held = placeOf(*c) + (c->terrain.empty() ? "" : " / " + c->terrain);
    std::string variant = c->paramsLabel + (grids.size() > 1 ? ", grid " + std::to_string(c->grid) : "");
    points.push_back({c, px, held, c->scheme + "|" + variant + "|" + held, c->scheme + " " + variant});
  }
  if (auto p = varying(points); !p.empty()) {
    auto pixels = [&](const std::vector<double>& xs) {
      AxisDomain d = log2Domain(xs);
      for (auto it = names.rbegin(); it != names.rend(); ++it)
        d.labelExpr = "datum.value == " + numberLabel(it->first) + " ? '" + it->second +
                      "' : " + (d.labelExpr.empty() ? "datum.label" : d.labelExpr);
      return d;
    };
    charts.push_back(build(run,
                           {"scale_resolution", "Cost vs resolution", "resolution, pixels per frame",
                            "one line per scheme and setting, everything but the resolution held; log axis", false},
                           p, pixels));
  }

  // Against each scheme's swept parameter (errbound: max_error_px): one panel row per scheme.
  points.clear();
  for (auto* c : cases)
    for (auto& [name, value] : c->params.items()) {
      if (!value.is_number()) continue;
      std::string others;  // the other parameters, held along the line
      for (auto& [k, v] : c->params.items())
        if (k != name) others += (others.empty() ? "" : ", ") + k + "=" + v.dump();
      std::string held = placeOf(*c) + (c->terrain.empty() ? "" : " / " + c->terrain) +
                         (resolutions.size() > 1 ? ", " + resolutionOf(*c) : "") +
                         (grids.size() > 1 ? ", grid " + std::to_string(c->grid) : "") +
                         (others.empty() ? "" : ", " + others);
      points.push_back(
          {c, value.get<double>(), name + " (" + c->scheme + ")", c->scheme + "|" + name + "|" + held, held});
    }
  if (auto p = varying(points); !p.empty()) {
    Variable v{"scale_param", "Cost vs each scheme's parameter", "",
               "one panel per scheme and swept parameter (its values on the x axis), one line per path and setting "
               "of the others; panels share the y axis",
               true};
    charts.push_back(build(run, v, p, [](const std::vector<double>& xs) { return niceDomain(xs); }));
  }
  return charts;
}

}  // namespace lb
