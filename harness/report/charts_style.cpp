// Scheme colours and shapes shared by every chart and legend, and the links to a chart's files.
// Colours: mostly Paul Tol's "muted" qualitative scheme (https://personal.sron.nl/~pault/), designed
// to stay distinct under the common colour-vision deficiencies; each scheme also has its own point
// shape (no two alike, 20 in all), so no chart relies on hue alone and a grey print still tells
// them apart.
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

// Room for 20 schemes: the registered ones by name, then four spare styles that a scheme without an
// entry takes in registry order (a scheme added before its entry) or, when not registered, by hash.
const SchemeStyle kSpare[] = {
    {"", "#B8860B", kHalfDisc}, {"", "#6699CC", kTrapezoid}, {"", "#663333", kChevron}, {"", "#66AA55", kTee}};

}  // namespace

const std::vector<SchemeStyle>& schemeStyles() {
  static const std::vector<SchemeStyle> table = {
      {"uniform", "#777777", "square"},  // the baseline: neutral grey
      {"reference", "#332288", "cross"},
      {"sphere", "#88CCEE", "circle"},
      {"sphere-edge", "#44AA99", "triangle-up"},
      {"sphere-rings", "#117733", "triangle-down"},
      {"distance", "#999933", "diamond"},
      {"interlock", "#DDCC77", "triangle-right"},
      {"density", "#CC6677", "triangle-left"},
      {"planefit", "#882255", kRing},
      {"phong", "#AA4499", kStar},
      {"errbound", "#000000", kX},  // black: its sweep is the dashed reference front
      // The instanced-grid schemes: the CDLOD pair in blue and dark teal, clipmaps in orange.
      {"cdlod", "#0077BB", kHexagon},
      {"cdlod-sse", "#005F56", kPentagon},
      {"clipmap", "#EE7733", kFrame},
      // The GPU-indirect trees in magenta and red, bow-tie and hourglass: one LOD drawn two ways.
      {"cbt", "#EE3377", kBowtie},
      {"cbt-ts", "#CC3311", kHourglass},
  };
  return table;
}

const std::vector<SchemeStyle>& spareSchemeStyles() {
  static const std::vector<SchemeStyle> spare(std::begin(kSpare), std::end(kSpare));
  return spare;
}

namespace {

// FNV-1a: a fixed hash (std::hash may differ between standard libraries).
uint32_t fnv1a(const std::string& s) {
  uint32_t h = 2166136261u;
  for (unsigned char ch : s) h = (h ^ ch) * 16777619u;
  return h;
}

const SchemeStyle& styleOf(const std::string& scheme) {
  for (auto& s : schemeStyles())
    if (scheme == s.scheme) return s;
  size_t unstyled = 0;  // registered schemes without an entry, in registry order
  for (const Scheme* r : allSchemes()) {
    const std::string& name = r->info().name;
    bool styled = std::any_of(schemeStyles().begin(), schemeStyles().end(), [&](auto& s) { return name == s.scheme; });
    if (styled) continue;
    if (name == scheme && unstyled < std::size(kSpare)) return kSpare[unstyled];
    ++unstyled;
  }
  return kSpare[fnv1a(scheme) % std::size(kSpare)];
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
