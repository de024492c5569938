#include "report/report_page.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include "report/report_tables.h"
#include "report/scenario_table.h"
#include "report/table.h"
#include "sweep/results.h"

namespace lb {

namespace {

// Strip order: what the frame looks like, then how it was tessellated, then what went wrong.
const char* const kModeOrder[] = {"shaded", "wireframe", "heatmap", "error", "cracks"};

struct Section {
  const char* id;
  const char* title;
  const char* intro;
};
const Section kChartSections[] = {
    {"speed", "Speed vs accuracy",
     "Cost against screen-space geometric error, one point per case. A scheme's Pareto front joins its settings "
     "that no other setting of the same scheme beats on both axes; the lower-left corner is better."},
    {"scale", "Scale study", "GPU time and triangles as the grid, the resolution or a scheme's parameter grows, everything else held."},
    {"histogram", "Triangle sizes",
     "How large the triangles are on screen. Bins are powers of two of the area in pixels; sub-pixel triangles "
     "waste rasterizer work, large ones lose detail."},
    {"timeline", "Along each path", "Per-frame cost and error along each camera path."},
};

class Writer {
 public:
  void heading(int level, const std::string& text, const std::string& id) {
    md_ += "\n" + std::string(size_t(level), '#') + " " + text + "\n\n";
    html_ +=
        "<h" + std::to_string(level) + " id=\"" + id + "\">" + htmlEscape(text) + "</h" + std::to_string(level) + ">\n";
  }
  void para(const std::string& text, const char* cls = nullptr) {
    md_ += (cls ? "> " : "") + text + "\n\n";
    html_ += std::string("<p") + (cls ? std::string(" class=\"") + cls + "\"" : "") + ">" + htmlEscape(text) + "</p>\n";
  }
  void table(const Table& t, const char* cls) {
    md_ += toMarkdown(t) + "\n";
    html_ += toHtml(t, cls);
  }
  void raw(const std::string& md, const std::string& html) {
    md_ += md;
    html_ += html;
  }
  Page page() const { return {md_, html_}; }

 private:
  std::string md_, html_;
};

void chartSection(Writer& w, const Section& s, const std::vector<Chart>& charts) {
  if (std::none_of(charts.begin(), charts.end(), [&](const Chart& c) { return c.section == s.id; })) return;  // scale: only when the run varies grid, resolution or a parameter
  w.heading(2, s.title, s.id);
  w.para(s.intro);
  for (auto& c : charts) {
    if (c.section != s.id) continue;
    if (!c.note.empty()) {
      w.para(c.note, "note");
      continue;
    }
    w.raw("![" + c.title + "](svg/" + c.id + ".svg)\n\n" + chartFilesMarkdown(c) + (c.caption.empty() ? "" : ". " + c.caption) + "\n\n",
          "<figure class=\"chart-box\"><div class=\"chart\" id=\"chart-" + c.id + "\" data-chart=\"" + c.id +
              "\"></div>" + chartFilesHtml(c) + (c.caption.empty() ? "" : "<figcaption>" + htmlEscape(c.caption) + "</figcaption>") +
              "</figure>\n");
  }
}

void stripSection(Writer& w, const std::vector<Strip>& strips, const std::string& runHref) {
  w.heading(2, "Images", "images");
  if (strips.empty()) {
    w.para("No images: the run wrote none (config `images`), or none for the chosen frames.", "note");
    return;
  }
  w.para("Chosen frames and each case's worst frames (cracks, popping, error), in the modes the run rendered.");
  for (auto& s : strips) {
    std::string caption = s.c->label + ", " + s.c->scenario + ", frame " + std::to_string(s.frame);
    std::string worst = worstOf(*s.c, s.frame);
    if (!worst.empty()) caption += " (worst frame: " + worst + ")";
    std::string md = "**" + caption + "**\n\n", html;
    html += "<figure class=\"strip\" id=\"" + imageAnchor(s.c->id, s.frame) + "\"><figcaption>" + htmlEscape(caption) +
            "</figcaption><div class=\"shots\">";
    for (auto& [mode, file] : s.images) {
      md += "![" + mode + "](" + runHref + "/" + file + ") ";
      html += "<div class=\"shot\"><img src=\"" + htmlEscape(runHref + "/" + file) + "\" alt=\"" + htmlEscape(mode) +
              "\"><span>" + htmlEscape(mode) + "</span></div>";
    }
    w.raw(md + "\n\n", html + "</div></figure>\n");
  }
}

}  // namespace

std::vector<Strip> imageStrips(const ReportRun& run, const std::vector<int>& frames, std::vector<std::string>& notes) {
  std::vector<Strip> strips;
  std::set<int> shown;
  for (auto& c : run.cases) {
    auto imgs = run.images.find(c.id);
    if (imgs == run.images.end()) continue;
    std::set<int> chosen;
    for (auto& [frame, modes] : imgs->second)
      if (frames.empty() || std::count(frames.begin(), frames.end(), frame)) chosen.insert(frame);
    for (int f : worstFrames(c))
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

Page buildPage(const ReportRun& run, const std::vector<Chart>& charts, const std::vector<Strip>& strips,
               const std::string& runHref, const std::vector<std::string>& notes) {
  Writer w;
  w.raw("# lodbench report: " + run.name + "\n\n", "<h1>lodbench report: " + htmlEscape(run.name) + "</h1>\n");
  w.para("Run directory " + run.dir + ", " + std::to_string(run.cases.size()) + " cases; report written " +
         isoTimeUtc() + ".");
  for (auto& n : notes) w.para(n, "note");

  w.heading(2, "Context", "context");
  w.table(contextTable(run), "context");
  if (run.context.contains("config")) {
    std::string config = run.context["config"].dump(2);
    w.raw("<details><summary>Config as run</summary>\n\n```json\n" + config + "\n```\n\n</details>\n\n",
          "<details><summary>Config as run</summary><pre>" + htmlEscape(config) + "</pre></details>\n");
  }

  for (const Section& s : kChartSections) chartSection(w, s, charts);

  w.heading(2, "Stability", "stability");
  w.para(
      "Per scheme and path, the worst case of each: cracks (analytic: shared patch edges whose tessellation "
      "factors differ; pixels: background showing through the terrain), popping (mean and p99 absolute RGB "
      "difference, 0-255, between a frame rendered with the previous frame's LOD and with the live LOD), and the "
      "share of measured frames where a visible patch hit factor 64. Links go to the worst frame's images.");
  w.table(stabilityTable(run, runHref), "stability");
  if (const std::string d = scenarioDescription(run); !d.empty()) {
    // Scenario runs (configs/scenarios/): what failure to look for, and each case's figure for it.
    w.para("Scenario: " + d);
    if (const std::string metric = scenarioMetric(d); !metric.empty())
      w.table(scenarioTable(run, metric, runHref), "scenario");
  }

  w.heading(2, "Failed and skipped cases", "problems");
  Table problems = problemTable(run);
  if (problems.rows.empty())
    w.para("None: every case ran.");
  else
    w.table(problems, "problems");

  // Clock control (issue 13): cases whose calibration workload drifted over the timed frames.
  std::string flagged;
  int calibrated = 0;
  for (const ReportCase& c : run.cases) {
    auto cal = c.summary.find("calibration");
    if (cal == c.summary.end() || !cal->is_object()) continue;
    ++calibrated;
    if (cal->value("flagged", false)) {
      auto d = cal->find("drift");
      char pct[32] = "unknown";
      if (d != cal->end() && d->is_number()) std::snprintf(pct, sizeof pct, "%+.1f%%", d->get<double>() * 100);
      flagged += (flagged.empty() ? "" : ", ") + c.id + " (" + pct + ")";
    }
  }
  if (calibrated > 0)
    w.para(flagged.empty() ? "Clock control: no case's calibration drifted by more than 2% over its timed frames."
                           : "Clock control: calibration drifted by more than 2% over the timed frames of " + flagged + ".",
           "note");

  w.heading(2, "Every case", "cases");
  std::vector<std::string> omitted;
  Table cases = caseTable(run, omitted);
  w.para(
      "Timing statistics over timed frames; error, image and stability metrics are means (cracks: maximum) over "
      "measured frames. – marks a metric the case does not have.");
  w.table(cases, "cases");
  if (!omitted.empty()) {
    std::string list;
    for (auto& o : omitted) list += (list.empty() ? "" : ", ") + o;
    w.para("Columns left out, no case has them: " + list + ".", "note");
  }

  stripSection(w, strips, runHref);
  return w.page();
}

}  // namespace lb
