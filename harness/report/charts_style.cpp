// Scheme colours and shapes shared by every chart and legend, and the links to a chart's files.
// Colours: mostly Paul Tol's "muted" qualitative scheme (https://personal.sron.nl/~pault/), designed
// to stay distinct under the common colour-vision deficiencies; each scheme also has its own point
// shape (no two alike among the first 20), so no chart relies on hue alone and a grey print still
// tells them apart.
#include <algorithm>
#include <cstdint>

#include "report/charts.h"
#include "report/table.h"
#include "schemes/registry.h"

namespace lb {

using nlohmann::json;

namespace {

// Point shapes beyond Vega's built-in ones (its thin "wedge", "arrow" and "stroke" read as lines), as SVG paths in
// Vega's unit square (-1..1).
constexpr const char* kStar =
    "M0,-1L0.2245,-0.309L0.951,-0.309L0.3633,0.118L0.5878,0.809L0,0.382L-0.5878,0.809L-0.3633,0.118L-0.951,-0.309L-"
    "0.2245,-0.309Z";
constexpr const char* kPentagon = "M0,-1L0.951,-0.309L0.588,0.809L-0.588,0.809L-0.951,-0.309Z";
constexpr const char* kHexagon = "M0,-1L0.866,-0.5L0.866,0.5L0,1L-0.866,0.5L-0.866,-0.5Z";
constexpr const char* kX = "M-1,-0.6L-0.6,-1L0,-0.4L0.6,-1L1,-0.6L0.4,0L1,0.6L0.6,1L0,0.4L-0.6,1L-1,0.6L-0.4,0Z";
constexpr const char* kBowtie = "M-1,-1L0,0L-1,1ZM1,-1L0,0L1,1Z";
constexpr const char* kHourglass = "M-1,-1L1,-1L0,0ZM-1,1L1,1L0,0Z";
constexpr const char* kHalfDisc = "M-1,0.4A1,1 0 0 1 1,0.4Z";
constexpr const char* kTrapezoid = "M-0.5,-0.8L0.5,-0.8L1,0.8L-1,0.8Z";
constexpr const char* kChevron = "M-1,-0.8L0,0.2L1,-0.8L1,0L0,1L-1,0Z";
constexpr const char* kTee = "M-1,-1H1V-0.4H0.3V1H-0.3V-0.4H-1Z";
// Rings: an outer outline and an inner one wound the other way, so the middle stays empty.
constexpr const char* kRing =
    "M0,-1A1,1 0 1 1 0,1A1,1 0 1 1 0,-1ZM0,-0.45A0.45,0.45 0 1 0 0,0.45A0.45,0.45 0 1 0 0,-0.45Z";
constexpr const char* kFrame = "M-1,-1H1V1H-1ZM-0.45,-0.45V0.45H0.45V-0.45Z";

}  // namespace

// Registry index i takes entry i, so a new scheme, built-in or a plugin's, gets a style of its own
// without an edit here. The order keeps every built-in scheme's style as it was when each had a
// named entry (the comments), so earlier reports and published charts keep their colours.
const std::vector<SchemeStyle>& schemePalette() {
  static const std::vector<SchemeStyle> palette = {
      {"#777777", "square"},          // uniform: the baseline in neutral grey
      {"#88CCEE", "circle"},          // sphere
      {"#DDCC77", "triangle-right"},  // interlock
      {"#117733", "triangle-down"},   // sphere-rings
      {"#CC6677", "triangle-left"},   // density
      {"#AA4499", kStar},             // phong
      {"#999933", "diamond"},         // distance
      {"#332288", "cross"},           // reference
      {"#882255", kRing},             // planefit
      {"#000000", kX},                // errbound: black, its sweep is the dashed reference front
      {"#44AA99", "triangle-up"},     // sphere-edge
      // The instanced-grid schemes: the CDLOD pair in blue and dark teal, clipmaps in orange.
      {"#0077BB", kHexagon},   // cdlod
      {"#005F56", kPentagon},  // cdlod-sse
      {"#EE7733", kFrame},     // clipmap
      // The GPU-indirect trees in magenta and red, bow-tie and hourglass: one LOD drawn two ways.
      {"#EE3377", kBowtie},     // cbt
      {"#CC3311", kHourglass},  // cbt-ts
      // Schemes added since, then plugins' schemes, in registry order.
      {"#B8860B", kHalfDisc},
      {"#6699CC", kTrapezoid},
      {"#663333", kChevron},
      {"#66AA55", kTee},
  };
  return palette;
}

namespace {

// FNV-1a: a fixed hash (std::hash may differ between standard libraries).
uint32_t fnv1a(const std::string& s) {
  uint32_t h = 2166136261u;
  for (unsigned char ch : s) h = (h ^ ch) * 16777619u;
  return h;
}

SchemeStyle styleOf(const std::string& scheme) {
  const std::vector<SchemeStyle>& palette = schemePalette();
  const size_t n = palette.size(), spare = 4;  // the last four: after the built-in schemes the comments name
  const std::vector<const Scheme*>& schemes = allSchemes();
  for (size_t i = 0; i < schemes.size(); ++i)
    if (schemes[i]->info().name == scheme) {
      if (i < n) return palette[i];
      // Past the palette: its colours again, each with another entry's shape.
      return {palette[n - spare + i % spare].colour, palette[(i / spare) % (n - spare)].shape};
    }
  // Not registered (a control, or a plugin's scheme whose library the report could not load): a
  // spare style picked by a hash, the same every time.
  return palette[n - spare + fnv1a(scheme) % spare];
}

}  // namespace

std::string schemeColour(const std::string& scheme) {
  return styleOf(scheme).colour;
}

std::string schemeShape(const std::string& scheme) {
  return styleOf(scheme).shape;
}

std::vector<std::string> chartSchemes(const ReportRun& run) {
  std::vector<std::string> out;
  for (auto& s : run.schemes)
    if (std::any_of(run.cases.begin(), run.cases.end(), [&](auto& c) { return c.scheme == s && c.status == "ok"; }))
      out.push_back(s);
  return out;
}

json schemeColor(const ReportRun& run) {
  std::vector<std::string> domain = chartSchemes(run), range;
  for (auto& s : domain) range.push_back(schemeColour(s));
  return {
      {"field", "scheme"}, {"type", "nominal"}, {"title", "scheme"}, {"scale", {{"domain", domain}, {"range", range}}}};
}

json schemeShapeEncoding(const ReportRun& run) {
  std::vector<std::string> domain = chartSchemes(run), range;
  for (auto& s : domain) range.push_back(schemeShape(s));
  return {
      {"field", "scheme"}, {"type", "nominal"}, {"title", "scheme"}, {"scale", {{"domain", domain}, {"range", range}}}};
}

std::string chartFilesMarkdown(const Chart& c) {
  return "[SVG](svg/" + c.id + ".svg) · [PNG](png/" + c.id + ".png) · [spec](charts/" + c.id + ".vl.json)";
}

std::string chartFilesHtml(const Chart& c) {
  std::string id = htmlEscape(c.id);
  return "<div class=\"chart-files\"><a href=\"svg/" + id + ".svg\">SVG</a> · <a href=\"png/" + id +
         ".png\">PNG</a> · <a href=\"charts/" + id + ".vl.json\">spec</a></div>";
}

}  // namespace lb
