#pragma once
// The report's charts, declared as Vega-Lite specifications (https://vega.github.io/vega-lite/)
// over data rows computed here; report/render.mjs draws them (HTML, SVG and PNG). A chart without
// the metrics it needs is kept as a note saying why it was left out.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "report/run_data.h"

namespace lb {

struct Chart {
  std::string id;       // file stem: charts/<id>.vl.json, svg/<id>.svg, png/<id>.png
  std::string section;  // "speed", "scale", "histogram", "timeline"
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

// GPU ms and triangles vs mean and p95 screen-space error, with each scheme's Pareto front and
// the error-bounded scheme's sweep over its bound as the dashed reference front.
std::vector<Chart> speedCharts(const ReportRun& run);
// Scale study: GPU ms (median, p95) and triangles against grid, resolution and each
// scheme's swept parameter; only the charts whose variable the run varies.
std::vector<Chart> scaleCharts(const ReportRun& run);
// Triangle-size histograms (share of on-screen triangles per area bin), per scheme and path.
Chart histogramChart(const ReportRun& run);
// Per-frame GPU ms, triangles and error along each path.
std::vector<Chart> timelineCharts(const ReportRun& run);

// Links to a drawn chart's files (svg/<id>.svg, png/<id>.png), for the page next to each chart.
std::string chartFilesMarkdown(const Chart& c);
std::string chartFilesHtml(const Chart& c);

// --- Scheme colours (charts_style.cpp) ---------------------------------------------------------
// One fixed colour and point shape per scheme, the same in every chart, report and legend: Paul
// Tol's colour-blind-safe "muted" palette, black for the error-bounded reference front, grey for the
// uniform baseline. A scheme's style is the palette's entry at its registry index (schemes/registry.h),
// so no two of the first 20 schemes share a colour or a shape and a new scheme needs no edit here; a
// name the registry does not hold takes one of the spare entries, picked by a hash.
struct SchemeStyle {
  const char* colour;  // "#rrggbb"
  const char* shape;   // Vega point shape: a built-in name or an SVG path in the unit square
};
const std::vector<SchemeStyle>& schemePalette();
std::string schemeColour(const std::string& scheme);
std::string schemeShape(const std::string& scheme);

// Schemes with at least one finished case: the colour domain of the run's charts.
std::vector<std::string> chartSchemes(const ReportRun& run);
// Colour and shape encodings by scheme over chartSchemes(run), with each scheme's fixed style.
nlohmann::json schemeColor(const ReportRun& run);
nlohmann::json schemeShapeEncoding(const ReportRun& run);

// --- Small multiples (charts_panels.cpp) --------------------------------------------------------
// Panels per scheme (and path when the run has several), in scheme order, wrapped kPanelColumns to
// a row; a panel's settings are coloured by rank (1 = smallest value) with one fixed ramp.
constexpr int kPanelColumns = 4;
constexpr int kPanelWidth = 240;  // 4 panels with their axes fit the 1,400 px page
std::string panelOf(const ReportRun& run, const ReportCase& c);
std::vector<std::string> panelOrder(const ReportRun& run);
// 1-based rank of the case's setting among its scheme's finished settings (run.paramLabels order).
int settingRank(const ReportRun& run, const ReportCase& c);
// "tri_size 2 / 4 / 8": the parameters that vary between the scheme's settings, in rank order.
std::string settingsTitle(const ReportRun& run, const std::string& scheme);
// The case's values of the parameters that vary within its scheme ("4"; "4, 0.5"): point labels.
std::string settingLabel(const ReportRun& run, const ReportCase& c);
// Colour encoding of the data column "setting" (the rank), legend above the panels.
nlohmann::json settingColor(const ReportRun& run);
// Facet over the data column "panel", headers naming each panel's settings.
nlohmann::json panelFacet(const ReportRun& run);

// --- Axes (charts_axes.cpp) --------------------------------------------------------------------
// Positive data spanning more than this many decades is drawn on a log axis.
constexpr double kLogDecades = 1.5;
enum class AxisKind { Auto, Linear, Log };
struct AxisDomain {
  std::string type = "linear";  // "linear" or "log"
  double lo = 0, hi = 1;        // strictly outside every value: no point sits on the plot border
  std::vector<double> ticks;    // round values (1, 2, 2.5, 5 x 10^k; log: 1, 2, 5 x 10^k) in [lo, hi]
  std::string format = "~f";    // d3 format of the tick labels ("~s" for large counts)
  int base = 10;                // of a log axis
  std::string labelExpr;        // Vega expression naming ticks (e.g. pixels as "320x180"); "" none
};
// A padded domain with round ends and ticks; Auto picks log when the positive values span more
// than kLogDecades. Log is ignored (linear) when a value is <= 0. Non-finite values are ignored.
AxisDomain niceDomain(const std::vector<double>& values, AxisKind kind = AxisKind::Auto);
// A base-2 log axis with a tick at every distinct value (grid sizes), padded by a quarter octave.
AxisDomain log2Domain(const std::vector<double>& values);
// "log" when the positive values span more than kLogDecades, else "linear".
std::string scaleTypeFor(const std::vector<double>& values);
// Vega-Lite scale and axis of a domain (explicit domain and tick values, no automatic nice).
nlohmann::json scaleJson(const AxisDomain& d);
nlohmann::json axisJson(const AxisDomain& d);
// A positional encoding: field, quantitative, title (with " (log)" on log axes), scale, axis.
nlohmann::json positionEncoding(const std::string& field, const std::string& title, const AxisDomain& d);
// A cost axis' scale without a computed domain (faceted charts): log, or linear without zero.
nlohmann::json valueScale(const std::string& type);

}  // namespace lb
