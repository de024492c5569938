// Charts over frames (docs/design.md, Reports and regression checks): triangle-size histograms from the summaries'
// summed bins, and per-frame timelines along each camera path from the case files.
#include <cmath>

#include "report/charts.h"

namespace lb {

using nlohmann::json;

namespace {

constexpr int kHistBins = 15;

struct Series {
  const char* id;
  const char* field;  // per-frame record key
  const char* title;
  const char* axis;  // y-axis title with unit, short: it repeats on every row of panels
  const char* what;  // the subtitle's definition of the value
  bool measured;     // only on measurement frames: draw points as well as lines
};
constexpr Series kSeries[] = {
    {"timeline_gpu_ms", "gpu_ms", "GPU time along each path", "GPU ms", "GPU time of the frame (ms)", false},
    {"timeline_triangles", "clip_invocations", "Triangles along each path", "triangles",
     "triangles reaching the clipper per frame", false},
    {"timeline_error", "err_mean_px", "Screen-space error along each path", "mean error px",
     "mean screen-space error over terrain pixels (px)", true},
    {"timeline_coverage", "coverage_missing_px", "Missing terrain along each path", "missing px",
     "pixels where the ray-cast truth shows terrain and the scheme drew none", true},
};

std::string fraction(int exponent) {  // 2^exponent as "1/8", "1/2", "1", "512"
  return exponent < 0 ? "1/" + std::to_string(1 << -exponent) : std::to_string(1 << exponent);
}

json timelineSpec(const ReportRun& run, const Series& s, const std::string& yScale) {
  json x = {{"field", "frame"},
            {"type", "quantitative"},
            {"title", "frame"},
            {"axis", {{"format", "d"}, {"tickMinStep", 1}}}};
  json y = {{"field", s.field}, {"type", "quantitative"}, {"title", s.axis}, {"scale", valueScale(yScale)}};
  // Vega picks the shared y domain, so ticks cannot be fixed here: a log axis gets decades and
  // their 2s and 5s (Vega's default draws every 1..9 x 10^k).
  if (yScale == "log") {
    y["title"] = std::string(s.axis) + " (log)";
    y["axis"] = {
        {"values", {0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1,   2,   5,   10,  20,  50,  100, 200,
                    500,   1e3,   2e3,   5e3,  1e4,  2e4,  5e4, 1e5, 2e5, 5e5, 1e6, 2e6, 5e6, 1e7, 2e7, 5e7, 1e8}},
        {"format", "~f"}};
  }
  json encoding = {{"x", x},
                   {"y", y},
                   {"color", settingColor(run)},
                   {"detail", {{"field", "case_id"}, {"type", "nominal"}}},
                   {"tooltip", json::array({{{"field", "label"}, {"title", "case"}},
                                            {{"field", "frame"}},
                                            {{"field", s.field}, {"title", s.axis}, {"format", ".4~g"}}})}};
  json layers = json::array(
      {{{"mark", {{"type", "line"}, {"strokeWidth", 1.5}, {"interpolate", "linear"}}}, {"encoding", encoding}}});
  if (s.measured)
    layers.push_back({{"mark", {{"type", "point"}, {"filled", true}, {"size", 24}}}, {"encoding", encoding}});
  // One panel per scheme with its few settings, on one shared y axis: schemes compare across panels.
  return {{"$schema", kVegaLiteSchema},
          {"title",
           {{"text", s.title},
            {"subtitle", std::string(s.what) + ", " + (s.measured ? "measured frames only" : "every timed frame") +
                             "; one panel per scheme, colour: its setting"}}},
          {"data", {{"url", "data/timeline.json"}}},
          {"transform", {{{"filter", std::string("isValid(datum.") + s.field + ")"}}}},
          {"facet", panelFacet(run)},
          {"columns", kPanelColumns},
          {"spec", {{"width", kPanelWidth}, {"height", 130}, {"layer", layers}}}};
}

}  // namespace

std::vector<std::string> histogramBinLabels() {
  std::vector<std::string> labels{"<1/8"};
  for (int i = -3; i < 10; ++i) labels.push_back(fraction(i) + "-" + fraction(i + 1));
  labels.push_back(">=1024");
  return labels;
}

Chart histogramChart(const ReportRun& run) {
  Chart chart;
  chart.id = chart.dataName = "triangle_sizes";
  chart.section = "histogram";
  chart.title = "Triangle sizes on screen";
  std::vector<std::string> labels = histogramBinLabels();
  std::string missing;
  for (auto& c : run.cases) {
    if (c.status != "ok") continue;
    auto h = c.summary.find("hist_total");
    double total = 0;
    if (h != c.summary.end() && h->is_array() && h->size() == kHistBins)
      for (auto& v : *h) total += v.is_number() ? v.get<double>() : 0;
    if (total <= 0) {
      missing += (missing.empty() ? "" : ", ") + c.label + " (" + c.scenario + ")";
      continue;
    }
    for (int i = 0; i < kHistBins; ++i) {
      double n = (*h)[i].is_number() ? (*h)[i].get<double>() : 0;
      chart.data.push_back({{"case_id", c.id},
                            {"scheme", c.scheme},
                            {"params", c.paramsLabel},
                            {"label", c.label},
                            {"scenario", c.scenario},
                            {"panel", panelOf(run, c)},
                            {"setting", settingRank(run, c)},
                            {"bin", labels[i]},
                            {"bin_index", i},
                            {"triangles", n},
                            {"share", 100.0 * n / total}});
    }
  }
  if (chart.data.empty()) {
    chart.note = chart.title +
                 ": left out, no case has a triangle-size histogram (hist_total): the run had no "
                 "measurement passes, or every case failed.";
    return chart;
  }
  if (!missing.empty()) chart.caption = "Not shown (no histogram): " + missing + ".";
  json tooltip = json::array({{{"field", "label"}, {"title", "case"}},
                              {{"field", "bin"}, {"title", "area (px²)"}},
                              {{"field", "share"}, {"title", "share (%)"}, {"format", ".1f"}},
                              {{"field", "triangles"}, {"title", "triangles (all measured frames)"}}});
  chart.spec = {
      {"$schema", kVegaLiteSchema},
      {"title",
       {{"text", chart.title},
        {"subtitle", "share of on-screen, front-facing triangles per area bin, summed over measured frames"}}},
      {"data", {{"url", "data/" + chart.dataName + ".json"}}},
      {"facet", panelFacet(run)},
      {"columns", kPanelColumns},
      {"spec",
       {{"width", kPanelWidth},
        {"height", 150},
        {"mark", {{"type", "bar"}, {"tooltip", true}}},
        {"encoding",
         {{"x",
           {{"field", "bin"},
            {"type", "ordinal"},
            {"sort", labels},
            {"title", "triangle area on screen (px²)"},
            {"axis", {{"labelAngle", -45}}}}},
          {"xOffset", {{"field", "setting"}, {"type", "ordinal"}}},
          {"y", {{"field", "share"}, {"type", "quantitative"}, {"title", "share of triangles (%)"}}},
          {"color", settingColor(run)},
          {"tooltip", tooltip}}}}},
      // Each cell offsets only its own scheme's settings, so bars keep their width.
      {"resolve", {{"scale", {{"xOffset", "independent"}}}}}};
  return chart;
}

std::vector<Chart> timelineCharts(const ReportRun& run) {
  json rows = json::array();
  for (auto& c : run.cases) {
    if (c.status != "ok") continue;
    const int setting = settingRank(run, c);
    for (auto& f : c.frames) {
      json row = {{"case_id", c.id},         {"scheme", c.scheme},
                  {"params", c.paramsLabel}, {"label", c.label},
                  {"scenario", c.scenario},  {"panel", panelOf(run, c)},
                  {"setting", setting},      {"frame", frameValue(f, "frame").value_or(0)}};
      for (const Series& s : kSeries) {
        auto v = frameValue(f, s.field);
        row[s.field] = v ? json(*v) : json(nullptr);
      }
      rows.push_back(std::move(row));
    }
  }
  std::vector<Chart> charts;
  for (const Series& s : kSeries) {
    Chart chart;
    chart.id = s.id;
    chart.dataName = "timeline";
    chart.section = "timeline";
    chart.title = s.title;
    std::vector<double> values;
    for (auto& r : rows)
      if (r[s.field].is_number()) values.push_back(r[s.field].get<double>());
    if (values.empty()) {
      chart.note = chart.title + ": left out, no frame has " + s.field +
                   (s.measured ? " (the run had no measurement passes)" : " (no case has per-frame records)") + ".";
    } else {
      chart.data = rows;
      chart.spec = timelineSpec(run, s, scaleTypeFor(values));
    }
    charts.push_back(std::move(chart));
  }
  return charts;
}

}  // namespace lb
