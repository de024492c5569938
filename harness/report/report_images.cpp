#include "report/report_images.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>

#include "render/image_io.h"
#include "report/report_tables.h"
#include "report/scenario_table.h"
#include "report/table.h"

namespace lb {

// The sky of images for people (render/image_io.h), as a CSS colour.
static std::string skyHex() {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", kSkyRgba[0], kSkyRgba[1], kSkyRgba[2]);
  return buf;
}

namespace {

// Strip order: what the frame looks like, then how it was tessellated, then what went wrong.
const char* const kModeOrder[] = {"shaded", "wireframe", "heatmap", "error", "cracks"};

std::string hex(int r, int g, int b) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", r, g, b);
  return buf;
}

std::string bar(const std::string& gradient, const std::vector<std::string>& ticks, const std::string& title) {
  std::string t;
  for (auto& s : ticks) t += "<span>" + htmlEscape(s) + "</span>";
  return "<div class=\"legend\"><span>" + htmlEscape(title) +
         "</span><div><div class=\"bar\" style=\"background:linear-gradient(to right," + gradient +
         ")\"></div><div class=\"ticks\">" + t + "</div></div>";
}

std::string swatch(const std::string& colour, const std::string& text) {
  return "<span><span class=\"swatch\" style=\"background:" + colour + "\"></span> " + htmlEscape(text) + "</span>";
}

std::string heatLegend(bool lit) {
  std::string g;
  for (int i = 0; i <= 12; ++i)
    g += (i ? "," : "") + heatColour(std::exp2(i / 2.0)) + " " + std::to_string(i * 100 / 12) + "%";
  return bar(g, {"1", "2", "4", "8", "16", "32", "64"}, "tessellation level (log2)") +
         (lit ? "<span>(heat map: times lighting, 25-100%)</span>" : "") + "</div>";
}

std::string errorLegend() {
  // Stops at 0, 0.5, 2, 4.5, 8 px lie at a quarter of the bar each (the sqrt scale).
  std::string g;
  const double px[] = {0, 0.5, 2, 4.5, 8};
  for (int i = 0; i < 5; ++i) {
    int v = errorGrey(px[i]);
    g += (i ? "," : "") + hex(v, v, v) + " " + std::to_string(i * 25) + "%";
  }
  return bar(g, {"0", "0.5", "2", "4.5", "≥ 8 px"}, "error (sqrt scale)") + swatch(skyHex(), "no terrain (sky)") +
         "</div>";
}

std::string crackLegend() {
  return "<div class=\"legend\">" + swatch("#ff0000", "crack: background shows through where the truth has terrain") +
         swatch("#2b2b2b", "the frame, dimmed to a third") + "</div>";
}

}  // namespace

std::pair<int, int> pngSize(const std::string& file) {
  // The IHDR chunk follows the 8-byte signature: length, "IHDR", then width and height, big-endian.
  unsigned char b[24] = {};
  std::FILE* f = std::fopen(file.c_str(), "rb");
  size_t got = f ? std::fread(b, 1, sizeof b, f) : 0;
  if (f) std::fclose(f);
  if (got < sizeof b || std::memcmp(b + 12, "IHDR", 4) != 0) return {0, 0};
  auto be = [&](int at) { return int(b[at]) << 24 | int(b[at + 1]) << 16 | int(b[at + 2]) << 8 | int(b[at + 3]); };
  return {be(16), be(20)};
}

std::string imageTag(const ReportRun& run, const std::string& runHref, const std::string& file,
                     const std::string& alt) {
  // Linked, not embedded: the browser fetches an image when it scrolls near (loading="lazy"); its
  // size up front keeps the page from jumping while images arrive.
  std::string tag = "<img src=\"" + htmlEscape(runHref + "/" + file) + "\" alt=\"" + htmlEscape(alt) +
                    "\" loading=\"lazy\" decoding=\"async\"";
  auto [w, h] = pngSize(run.dir + "/" + file);
  if (w > 0 && h > 0) tag += " width=\"" + std::to_string(w) + "\" height=\"" + std::to_string(h) + "\"";
  return tag + ">";
}

std::string heatColour(double level) {
  const double t = std::clamp(std::log2(std::max(level, 1.0)) / 6.0, 0.0, 1.0);
  auto ch = [&](double centre) {
    return int(std::lround(255 * std::clamp(1.5 - std::fabs(4.0 * t - centre), 0.0, 1.0)));
  };
  return hex(ch(3.0), ch(2.0), ch(1.0));
}

int errorGrey(double px) {
  return int(std::lround(255.0 * std::min(1.0, std::sqrt(std::max(px, 0.0) / 8.0))));
}

std::string legendHtml(const std::string& mode) {
  if (mode == "heatmap") return heatLegend(true);
  if (mode == "wireframe") return heatLegend(false);
  if (mode == "error") return errorLegend();
  if (mode == "cracks") return crackLegend();
  return "";
}

std::vector<Strip> imageStrips(const ReportRun& run, const std::vector<int>& frames, const std::string& scenarioMetric,
                               std::vector<std::string>& notes) {
  std::vector<Strip> strips;
  std::set<int> shown;
  for (auto& c : run.cases) {
    auto imgs = run.images.find(c.id);
    if (imgs == run.images.end()) continue;
    std::set<int> chosen;
    for (auto& [frame, modes] : imgs->second)
      if (frames.empty() || std::count(frames.begin(), frames.end(), frame)) chosen.insert(frame);
    std::vector<int> worst = worstFrames(c);
    if (!scenarioMetric.empty()) worst.push_back(scenarioWorstFrame(c, scenarioMetric));
    for (int f : worst)
      if (imgs->second.count(f)) chosen.insert(f);
    for (int frame : chosen) {
      Strip s{&c, frame, {}};
      std::map<std::string, std::string> modes = imgs->second.at(frame);
      for (const char* m : kModeOrder)
        if (modes.count(m)) {
          s.images.emplace_back(m, modes[m]);
          modes.erase(m);
        }
      for (auto& [m, file] : modes) s.images.emplace_back(m, file);  // modes added after this report was written
      strips.push_back(std::move(s));
      shown.insert(frame);
    }
  }
  for (int f : frames)
    if (!shown.count(f)) notes.push_back("--frames " + std::to_string(f) + ": no case has images of this frame.");
  return strips;
}

std::pair<std::string, std::string> imageSection(const ReportRun& run, const std::vector<Strip>& strips,
                                                 const std::string& runHref) {
  std::string md = "\n## Images\n\n", html = "<h2 id=\"images\">Images</h2>\n";
  // Worst frames the run has no image of: said once per case, marked for the browser test.
  std::string missing;
  for (const ReportCase& c : run.cases) {
    auto imgs = run.images.find(c.id);
    for (int f : worstFrames(c))
      if (imgs == run.images.end() || !imgs->second.count(f)) {
        Cell m = missingImageCell(c.id, f);
        md += "- " + c.label + ", " + c.scenario + ": worst frame (" + worstOf(c, f) + ") " + m.md + "\n";
        missing += "<li>" + htmlEscape(c.label + ", " + c.scenario + ": worst frame (" + worstOf(c, f) + ") ") +
                   m.html + "</li>";
      }
  }
  if (!missing.empty()) {
    md += "\n";
    html += "<p class=\"note\">Worst frames without images (the run's config did not image them):</p><ul>" + missing +
            "</ul>\n";
  }
  if (strips.empty()) {
    const char* none = "No images: the run wrote none (config `images`), or none for the chosen frames.";
    return {md + "> " + none + "\n\n", html + "<p class=\"note\">" + htmlEscape(none) + "</p>\n"};
  }
  const char* intro =
      "Chosen frames and each case's worst frames (cracks, popping, error), in the modes the run rendered. Click an "
      "image to enlarge it.";
  md += std::string(intro) +
        " Heat map and wireframe: tessellation level on a log2 scale, 1 blue, 8 green, 64 red. Error map: 0 px "
        "black to 8 px and more white (sqrt scale), the sky colour where there is no terrain. Crack mask: red crack "
        "pixels "
        "over the dimmed frame.\n\n";
  std::set<std::string> modes;
  for (auto& s : strips)
    for (auto& [mode, file] : s.images) modes.insert(mode);
  html += "<p>" + htmlEscape(intro) + "</p>\n<div class=\"legends\">";
  for (const char* m : {"heatmap", "wireframe", "error", "cracks"})
    if (modes.count(m) && !(std::string(m) == "wireframe" && modes.count("heatmap")))
      html += "<div><b>" + std::string(m) + "</b>" + legendHtml(m) + "</div>";
  html += "</div>\n";
  for (auto& s : strips) {
    std::string caption = s.c->label + ", " + s.c->scenario + ", frame " + std::to_string(s.frame);
    std::string worst = worstOf(*s.c, s.frame);
    if (!worst.empty()) caption += " (worst frame: " + worst + ")";
    md += "**" + caption + "**\n\n";
    html += "<figure class=\"strip\" id=\"" + imageAnchor(s.c->id, s.frame) + "\"><figcaption>" + htmlEscape(caption) +
            "</figcaption><div class=\"shots\">";
    for (auto& [mode, file] : s.images) {
      md += "![" + mode + "](" + runHref + "/" + file + ") ";
      html += "<div class=\"shot\">" + imageTag(run, runHref, file, mode) + "<span>" + htmlEscape(mode) + "</span>" +
              legendHtml(mode) + "</div>";
    }
    md += "\n\n";
    html += "</div></figure>\n";
  }
  return {md, html};
}

}  // namespace lb
