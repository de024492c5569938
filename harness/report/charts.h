#pragma once
// The report's charts, declared as Vega-Lite specifications (https://vega.github.io/vega-lite/)
// over data rows computed here; report/render.mjs draws them (HTML and SVG). A chart without the
// metrics it needs is kept as a note saying why it was left out.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "report/run_data.h"

namespace lb {

struct Chart {
  std::string id;       // file stem: charts/<id>.vl.json, svg/<id>.svg
  std::string section;  // "speed", "histogram", "timeline"
  std::string title;
  std::string note;      // non-empty: the chart is omitted, and this says why
  std::string caption;   // shown under the chart (e.g. cases it could not include)
  std::string dataName;  // data/<dataName>.json, referenced by the spec's data url
  nlohmann::json spec;   // Vega-Lite
  nlohmann::json data = nlohmann::json::array();
};

constexpr const char* kVegaLiteSchema = "https://vega.github.io/schema/vega-lite/v6.json";
// Triangle-size histogram bins (docs/results-format.md: 15 bins, powers of two of pixel area).
std::vector<std::string> histogramBinLabels();

// GPU ms and triangles vs mean and p95 screen-space error, with each scheme's Pareto front.
std::vector<Chart> speedCharts(const ReportRun& run);
// Triangle-size histograms (share of on-screen triangles per area bin), per scheme and path.
Chart histogramChart(const ReportRun& run);
// Per-frame GPU ms, triangles and error along each path.
std::vector<Chart> timelineCharts(const ReportRun& run);

// Schemes with at least one finished case: the colour domain, the same in every chart.
std::vector<std::string> chartSchemes(const ReportRun& run);
// Shared encodings: scheme colours fixed by the run's scheme order, so every chart agrees.
nlohmann::json schemeColor(const ReportRun& run);
// "log" when the positive values span more than a factor kLogSpan, else "linear".
std::string scaleTypeFor(const std::vector<double>& values);
// A cost axis' scale: log, or linear without forcing zero in (costs sit far from zero).
nlohmann::json valueScale(const std::string& type);

}  // namespace lb
