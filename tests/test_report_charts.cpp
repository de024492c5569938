// The report's charts beyond the fixture: axis domains a paper can print (padded, round, log past
// 1.5 decades), the fixed colour-blind-safe scheme colours, the speed charts' fronts and errbound
// reference layer, and the scale-study charts that appear only when a run varies grid, resolution
// or a parameter. Runs are built in memory, so every expectation follows from the inputs here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "report/charts.h"
#include "schemes/registry.h"

using namespace lb;
using nlohmann::json;

namespace {

// A step is round when it is 1, 2, 2.5 or 5 times a power of ten.
bool roundStep(double step) {
  double p = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  double m = step / p;
  for (double r : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (std::fabs(m - r) < 1e-9) return true;
  return false;
}

bool oneTwoFive(double v) {
  double p = std::pow(10.0, std::floor(std::log10(v) + 1e-9));
  double m = v / p;
  return std::fabs(m - 1) < 1e-9 || std::fabs(m - 2) < 1e-9 || std::fabs(m - 5) < 1e-9 || std::fabs(m - 10) < 1e-9;
}

void expectPrintable(const AxisDomain& d, const std::vector<double>& v, const std::string& what) {
  double lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
  EXPECT_LT(d.lo, lo) << what;  // strictly: no point on the border
  EXPECT_GT(d.hi, hi) << what;
  ASSERT_GE(d.ticks.size(), 2u) << what;
  EXPECT_TRUE(std::is_sorted(d.ticks.begin(), d.ticks.end())) << what;
  EXPECT_GE(d.ticks.front(), d.lo - std::fabs(d.lo) * 1e-12 - 1e-12) << what;
  EXPECT_LE(d.ticks.back(), d.hi + std::fabs(d.hi) * 1e-12 + 1e-12) << what;
  if (d.type == "linear") {
    double step = d.ticks[1] - d.ticks[0];
    EXPECT_TRUE(roundStep(step)) << what << " step " << step;
    EXPECT_DOUBLE_EQ(d.ticks.front(), d.lo) << what;  // the ends are ticks
    EXPECT_DOUBLE_EQ(d.ticks.back(), d.hi) << what;
    EXPECT_LE(d.ticks.size(), 12u) << what;
    for (size_t i = 1; i < d.ticks.size(); ++i) EXPECT_NEAR(d.ticks[i] - d.ticks[i - 1], step, step * 1e-9) << what;
    for (double t : d.ticks) EXPECT_NEAR(t / step, std::round(t / step), 1e-9) << what << " tick " << t;
  } else {
    EXPECT_TRUE(oneTwoFive(d.lo)) << what << " lo " << d.lo;
    EXPECT_TRUE(oneTwoFive(d.hi)) << what << " hi " << d.hi;
    for (double t : d.ticks) EXPECT_TRUE(oneTwoFive(t)) << what << " tick " << t;
  }
}

ReportCase makeCase(const std::string& scheme, json params, const std::string& path, int w, int h, int grid,
                    double gpuMs, double triangles, std::optional<double> errPx = std::nullopt) {
  ReportCase c;
  c.scheme = scheme;
  c.params = params;
  c.status = "ok";
  c.path = "configs/paths/" + path + ".csv";
  c.terrain = "proc129s1";
  c.width = w;
  c.height = h;
  c.grid = grid;
  c.paramsLabel = params.empty() ? "defaults" : params.dump();
  c.label = scheme + " " + c.paramsLabel;
  c.id = scheme + c.paramsLabel + "_" + path + "_" + std::to_string(w) + "x" + std::to_string(h) + "_g" +
         std::to_string(grid);
  c.scenario = path;
  c.summary = {{"gpu_ms", {{"median", gpuMs}, {"p95", gpuMs * 1.25}}}, {"triangles", {{"median", triangles}}}};
  if (errPx) c.summary["err_mean_px"] = {{"mean", *errPx}}, c.summary["err_p95_px"] = {{"mean", *errPx * 3}};
  return c;
}

ReportRun makeRun(std::vector<ReportCase> cases) {
  ReportRun run;
  run.cases = std::move(cases);
  for (auto& c : run.cases) {
    if (std::find(run.schemes.begin(), run.schemes.end(), c.scheme) == run.schemes.end())
      run.schemes.push_back(c.scheme);
    if (std::find(run.scenarios.begin(), run.scenarios.end(), c.scenario) == run.scenarios.end())
      run.scenarios.push_back(c.scenario);
  }
  return run;
}

// Every object in a spec tree, depth first.
void visit(const json& j, const std::function<void(const json&)>& f) {
  if (j.is_object()) f(j);
  if (j.is_object() || j.is_array())
    for (auto& v : j) visit(v, f);
}

std::vector<json> layersWith(const json& spec, const std::function<bool(const json&)>& pred) {
  std::vector<json> out;
  visit(spec, [&](const json& o) {
    if (o.contains("mark") && pred(o)) out.push_back(o);
  });
  return out;
}

const Chart* findChart(const std::vector<Chart>& charts, const std::string& id) {
  for (auto& c : charts)
    if (c.id == id) return &c;
  return nullptr;
}

// A sweep: uniform levels, sphere tri_size, errbound max_error_px, on two paths.
ReportRun speedRun(bool withErrbound) {
  std::vector<ReportCase> cases;
  for (std::string path : {"flyover", "lowalt"}) {
    for (int level : {2, 8, 32})
      cases.push_back(makeCase("uniform", {{"level", level}}, path, 320, 180, 32, 0.2 * level, 2000.0 * level * level,
                               8.0 / level));
    for (double t : {2.0, 4.0, 8.0})
      cases.push_back(makeCase("sphere", {{"tri_size", t}}, path, 320, 180, 32, 4 / t, 90000 / t, 0.1 * t));
    if (withErrbound)
      for (double b : {0.5, 1.0, 2.0})
        cases.push_back(makeCase("errbound", {{"max_error_px", b}}, path, 320, 180, 32, 3 / b, 70000 / b, 0.3 * b));
  }
  return makeRun(cases);
}

}  // namespace

TEST(ReportAxes, LinearDomainsArePaddedAndRound) {
  for (auto& v : std::vector<std::vector<double>>{
           {0.93, 1.4, 2.71}, {0, 10}, {5, 5}, {-3.2, 4.1}, {1001, 1009.5}, {0.0213, 0.0297}})
    expectPrintable(niceDomain(v), v, json(v).dump());
  AxisDomain d = niceDomain({0.93, 1.4, 2.71});
  EXPECT_EQ(d.type, "linear");
  EXPECT_EQ(d.ticks, (std::vector<double>{0.5, 1, 1.5, 2, 2.5, 3}));
  // Positive data never gets a negative axis; a band of one value is centred on it.
  EXPECT_GE(niceDomain({0.5, 9}).lo, 0);
  AxisDomain one = niceDomain({5});
  EXPECT_LT(one.lo, 5);
  EXPECT_GT(one.hi, 5);
}

TEST(ReportAxes, LogPastOneAndAHalfDecades) {
  EXPECT_EQ(niceDomain({1, 31}).type, "linear");  // log10(31) = 1.49
  EXPECT_EQ(niceDomain({1, 32}).type, "log");     // 1.51 decades
  EXPECT_EQ(scaleTypeFor({1, 32}), "log");
  EXPECT_EQ(niceDomain({0, 1000}).type, "linear");  // a log axis cannot show zero
  EXPECT_EQ(niceDomain({1, 1000}, AxisKind::Linear).type, "linear");
  EXPECT_EQ(niceDomain({100, 200}, AxisKind::Log).type, "log");
  EXPECT_EQ(niceDomain({-1, 200}, AxisKind::Log).type, "linear");
  // GPU time with the reference scheme at 20x the others, triangles over three decades, error px.
  for (auto& v :
       std::vector<std::vector<double>>{{0.41, 0.55, 9.8}, {1800, 52000, 2.1e6}, {0.04, 0.9, 3.3}, {100, 200}})
    expectPrintable(niceDomain(v, v.size() == 2 ? AxisKind::Log : AxisKind::Auto), v, json(v).dump());
  AxisDomain tri = niceDomain({1800, 52000, 2.1e6});
  EXPECT_EQ(tri.type, "log");
  EXPECT_EQ(tri.format, "~s");  // 10k, 1M
  EXPECT_EQ(niceDomain({0.04, 0.9, 3.3}).format, "~f");
  json scale = scaleJson(tri);
  EXPECT_EQ(scale["type"], "log");
  EXPECT_EQ(scale["domain"], json({tri.lo, tri.hi}));
  EXPECT_EQ(scale["nice"], false);
  EXPECT_EQ(axisJson(tri)["values"], json(tri.ticks));
  EXPECT_NE(positionEncoding("triangles", "triangles", tri)["title"].get<std::string>().find("(log)"),
            std::string::npos);
}

TEST(ReportAxes, Log2AxisTicksEveryGrid) {
  AxisDomain d = log2Domain({32, 16, 16, 64});
  EXPECT_EQ(d.type, "log");
  EXPECT_EQ(d.ticks, (std::vector<double>{16, 32, 64}));
  EXPECT_LT(d.lo, 16);
  EXPECT_GT(d.hi, 64);
  EXPECT_EQ(scaleJson(d)["base"], 2);
}

TEST(ReportStyle, EverySchemeHasItsOwnFixedColourAndShape) {
  std::set<std::string> colours, shapes;
  for (const SchemeStyle& s : schemePalette()) {
    EXPECT_TRUE(std::regex_match(std::string(s.colour), std::regex("#[0-9A-Fa-f]{6}"))) << s.colour;
    colours.insert(s.colour);
    shapes.insert(s.shape);
  }
  EXPECT_EQ(schemePalette().size(), 20u) << "room for 20 schemes";
  EXPECT_EQ(colours.size(), schemePalette().size()) << "two palette entries share a colour";
  EXPECT_EQ(shapes.size(), schemePalette().size()) << "two palette entries share a point shape";
  // Vega's "triangle" is its "triangle-up": one of them only.
  EXPECT_FALSE(shapes.count("triangle") && shapes.count("triangle-up"));
  // Every registered scheme its own, from its place in the registry: no table to edit.
  std::set<std::pair<std::string, std::string>> styles;
  for (const Scheme* s : allSchemes())
    EXPECT_TRUE(styles.insert({schemeColour(s->info().name), schemeShape(s->info().name)}).second)
        << s->info().name << " shares a style";
  // The built-in schemes keep the styles they had when each had a named entry.
  EXPECT_EQ(schemeColour("errbound"), "#000000");
  EXPECT_EQ(schemeColour("uniform"), "#777777");
  EXPECT_EQ(schemeColour("cbt-ts"), "#CC3311");
  // An unknown name: a valid colour, the same every time, not black (the reference front's).
  std::string c = schemeColour("not-a-scheme");
  EXPECT_TRUE(std::regex_match(c, std::regex("#[0-9A-Fa-f]{6}")));
  EXPECT_EQ(c, schemeColour("not-a-scheme"));
  EXPECT_EQ(schemeShape("not-a-scheme"), schemeShape("not-a-scheme"));
  EXPECT_NE(c, "#000000");
}

TEST(ReportCharts, SpeedChartsHaveFrontsErrboundReferenceAndFixedColours) {
  ReportRun run = speedRun(true);
  std::vector<Chart> charts = speedCharts(run);
  ASSERT_EQ(charts.size(), 2u);
  for (const Chart& chart : charts) {
    ASSERT_TRUE(chart.note.empty()) << chart.note;
    const json& spec = chart.spec;
    ASSERT_EQ(spec["vconcat"].size(), 2u) << "one row per path";
    auto fronts = layersWith(spec, [](const json& o) {
      return o["mark"].value("type", "") == "line" && o.dump().find("datum.on_front") != std::string::npos;
    });
    auto reference = layersWith(
        spec, [](const json& o) { return o["mark"].value("type", "") == "line" && o["mark"].contains("strokeDash"); });
    EXPECT_EQ(fronts.size(), 4u) << "two paths x two error kinds";
    ASSERT_EQ(reference.size(), 4u);
    for (auto& r : reference) {
      EXPECT_EQ(r["mark"]["color"], schemeColour("errbound"));
      EXPECT_EQ(r["encoding"]["order"]["field"], "sweep");
      EXPECT_NE(r.dump().find("datum.errbound"), std::string::npos);
    }
    // Colours: the fixed table's, in the run's scheme order; the same object in every layer.
    auto points = layersWith(spec, [](const json& o) { return o["mark"].value("type", "") == "point"; });
    ASSERT_EQ(points.size(), 4u);
    for (auto& p : points) {
      EXPECT_EQ(p["encoding"]["color"]["scale"]["domain"], json({"uniform", "sphere", "errbound"}));
      EXPECT_EQ(p["encoding"]["color"]["scale"]["range"],
                json({schemeColour("uniform"), schemeColour("sphere"), schemeColour("errbound")}));
      // The x title says which error the panel plots; every panel's domain holds its points inside.
      std::string title = p["encoding"]["x"]["title"];
      std::string kind = p["transform"][0]["filter"]["and"][1]["equal"];
      EXPECT_EQ(title.rfind(kind.substr(0, kind.find(' ')), 0), 0u) << title << " in a " << kind << " panel";
      std::string scenario = p["transform"][0]["filter"]["and"][0]["equal"];
      std::string yField = p["encoding"]["y"]["field"];
      auto xd = p["encoding"]["x"]["scale"]["domain"], yd = p["encoding"]["y"]["scale"]["domain"];
      int inCell = 0;
      for (auto& row : chart.data) {
        if (row["scenario"] != scenario || row["error"] != kind) continue;
        ++inCell;
        EXPECT_GT(row["err_px"].get<double>(), xd[0].get<double>());
        EXPECT_LT(row["err_px"].get<double>(), xd[1].get<double>());
        EXPECT_GT(row[yField].get<double>(), yd[0].get<double>());
        EXPECT_LT(row[yField].get<double>(), yd[1].get<double>());
      }
      EXPECT_EQ(inCell, 9);
    }
  }
  // Triangles span 8000..2M: a log axis, said in its title.
  auto tri = layersWith(charts[1].spec, [](const json& o) { return o["mark"].value("type", "") == "point"; });
  EXPECT_EQ(tri[0]["encoding"]["y"]["scale"]["type"], "log");
  EXPECT_NE(tri[0]["encoding"]["y"]["title"].get<std::string>().find("(log)"), std::string::npos);

  // Without errbound cases there is no reference layer (an empty one makes Vega warn).
  std::vector<Chart> plain = speedCharts(speedRun(false));
  EXPECT_TRUE(layersWith(plain[0].spec, [](const json& o) { return o["mark"].contains("strokeDash"); }).empty());
  EXPECT_EQ(plain[0].spec["title"]["subtitle"].dump().find("dashed"), std::string::npos);
  EXPECT_NE(charts[0].spec["title"]["subtitle"].dump().find("dashed: errbound"), std::string::npos);
}

TEST(ReportCharts, ScaleChartsOnlyWhereTheRunVariesThem) {
  // Two schemes x grid 16/32 x two resolutions: grid and resolution charts, no parameter chart.
  std::vector<ReportCase> cases;
  for (int grid : {16, 32})
    for (auto [w, h] : {std::pair{160, 90}, std::pair{320, 180}}) {
      double px = double(w) * h;
      cases.push_back(
          makeCase("uniform", {{"level", 8}}, "flyover", w, h, grid, 1e-5 * px * grid / 16, 64.0 * grid * grid));
      cases.push_back(makeCase("sphere", {{"tri_size", 4}}, "flyover", w, h, grid, 2e-5 * px, px / 4));
    }
  ReportRun run = makeRun(cases);
  std::vector<Chart> charts = scaleCharts(run);
  ASSERT_EQ(charts.size(), 2u);
  const Chart* grid = findChart(charts, "scale_grid");
  const Chart* res = findChart(charts, "scale_resolution");
  ASSERT_TRUE(grid && res);
  EXPECT_EQ(grid->section, "scale");
  // One line per scheme and resolution, each with a point per grid.
  std::map<std::string, std::set<double>> xs;
  for (auto& r : grid->data) xs[r["series"]].insert(r["x"].get<double>());
  EXPECT_EQ(xs.size(), 4u);
  for (auto& [s, x] : xs) EXPECT_EQ(x, (std::set<double>{16, 32})) << s;
  auto panels = layersWith(grid->spec, [](const json& o) { return o["mark"].value("type", "") == "line"; });
  ASSERT_EQ(panels.size(), 3u) << "GPU median, GPU p95, triangles";
  std::vector<std::string> yTitles;
  for (auto& p : panels) {
    EXPECT_EQ(p["encoding"]["x"]["scale"]["base"], 2);
    EXPECT_EQ(p["encoding"]["x"]["axis"]["values"], json({16, 32}));
    EXPECT_EQ(p["encoding"]["color"]["scale"]["range"], json({schemeColour("uniform"), schemeColour("sphere")}));
    yTitles.push_back(p["encoding"]["y"]["title"]);
  }
  EXPECT_NE(yTitles[0].find("median"), std::string::npos);
  EXPECT_NE(yTitles[1].find("p95"), std::string::npos);
  EXPECT_NE(yTitles[2].find("triangles"), std::string::npos);
  // Resolution: pixels on a log axis, ticks named by the resolutions.
  auto resLine = layersWith(res->spec, [](const json& o) { return o["mark"].value("type", "") == "line"; });
  ASSERT_FALSE(resLine.empty());
  EXPECT_EQ(resLine[0]["encoding"]["x"]["scale"]["type"], "log");
  EXPECT_EQ(resLine[0]["encoding"]["x"]["axis"]["values"], json({14400, 57600}));
  std::string labels = resLine[0]["encoding"]["x"]["axis"]["labelExpr"];
  EXPECT_NE(labels.find("'160x90'"), std::string::npos);
  EXPECT_NE(labels.find("'320x180'"), std::string::npos);

  // A parameter sweep (errbound's max_error_px) gives the parameter chart, and nothing else.
  std::vector<ReportCase> sweep;
  for (double b : {0.5, 1.0, 2.0})
    sweep.push_back(makeCase("errbound", {{"max_error_px", b}}, "flyover", 320, 180, 32, 3 / b, 7e4 / b));
  sweep.push_back(makeCase("uniform", {{"level", 8}}, "flyover", 320, 180, 32, 1, 5e4));
  charts = scaleCharts(makeRun(sweep));
  ASSERT_EQ(charts.size(), 1u);
  EXPECT_EQ(charts[0].id, "scale_param");
  EXPECT_EQ(charts[0].data.size(), 3u) << "uniform's single level is no line";
  auto p = layersWith(charts[0].spec, [](const json& o) { return o["mark"].value("type", "") == "line"; });
  ASSERT_FALSE(p.empty());
  EXPECT_EQ(p[0]["encoding"]["x"]["title"].get<std::string>().rfind("max_error_px", 0), 0u);
  // Small multiples: one panel per scheme and parameter, wrapped, titled by both.
  const json& wrapped = charts[0].spec["vconcat"][0];
  EXPECT_EQ(wrapped["columns"], kPanelColumns);
  ASSERT_EQ(wrapped["concat"].size(), 1u);
  EXPECT_EQ(wrapped["concat"][0]["title"]["text"], "max_error_px (errbound)");

  // Nothing varies: no scale chart.
  EXPECT_TRUE(scaleCharts(makeRun({makeCase("uniform", {{"level", 8}}, "flyover", 320, 180, 32, 1, 5e4)})).empty());
}
