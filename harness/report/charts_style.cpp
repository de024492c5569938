// Scheme colours and shapes shared by every chart and legend, and the links to a chart's files.
// Colours: Paul Tol's "muted" qualitative scheme (https://personal.sron.nl/~pault/), designed to
// stay distinct under the common colour-vision deficiencies; each scheme also has its own point
// shape, so no chart relies on hue alone.
#include <algorithm>
#include <cstdint>

#include "report/charts.h"
#include "report/table.h"

namespace lb {

using nlohmann::json;

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
      {"planefit", "#882255", "wedge"},
      {"phong", "#AA4499", "triangle"},
      {"errbound", "#000000", "circle"},  // black: its sweep is the dashed reference front
      // The instanced-grid schemes: the CDLOD pair in related teals, clipmaps in orange.
      {"cdlod", "#009988", "square"},
      {"cdlod-sse", "#005F56", "diamond"},
      {"clipmap", "#EE7733", "cross"},
  };
  return table;
}

namespace {

const SchemeStyle* findStyle(const std::string& scheme) {
  for (auto& s : schemeStyles())
    if (scheme == s.scheme) return &s;
  return nullptr;
}

// FNV-1a: a fixed hash (std::hash may differ between standard libraries).
uint32_t fnv1a(const std::string& s) {
  uint32_t h = 2166136261u;
  for (unsigned char ch : s) h = (h ^ ch) * 16777619u;
  return h;
}

}  // namespace

std::string schemeColour(const std::string& scheme) {
  if (auto* s = findStyle(scheme)) return s->colour;
  // Okabe-Ito, without its black and yellow (taken, and unreadable on white).
  static const char* const fallback[] = {"#E69F00", "#56B4E9", "#009E73", "#0072B2", "#D55E00", "#CC79A7"};
  return fallback[fnv1a(scheme) % 6];
}

std::string schemeShape(const std::string& scheme) {
  if (auto* s = findStyle(scheme)) return s->shape;
  static const char* const fallback[] = {"circle", "square", "diamond", "cross"};
  return fallback[fnv1a(scheme) % 4];
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
