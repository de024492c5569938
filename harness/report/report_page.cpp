#include "report/report_page.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "report/equal_error.h"
#include "report/memory_table.h"
#include "report/page_assets.h"
#include "report/report_answer.h"
#include "report/report_glossary.h"
#include "report/report_howto.h"
#include "report/report_side_by_side.h"
#include "report/report_tables.h"
#include "report/scenario_table.h"
#include "report/table.h"
#include "results/write.h"

namespace lb {

namespace {

struct Section {
  const char* id;
  const char* title;
  const char* intro;
};
const Section kChartSections[] = {
    {"speed", "Speed vs accuracy",
     "Cost against screen-space geometric error, one point per case. A scheme's Pareto front joins its settings "
     "that no other setting of the same scheme beats on both axes; the lower-left corner is better."},
    {"scale", "Scale study",
     "GPU time and triangles as the grid, the resolution or a scheme's parameter grows, everything else held."},
    {"histogram", "Triangle sizes",
     "How large the triangles are on screen. Bins are powers of two of the area in pixels; sub-pixel triangles "
     "waste rasterizer work, large ones lose detail."},
    {"timeline", "Along each path", "Per-frame cost and error along each camera path."},
};

class Writer {
 public:
  explicit Writer(const ReportRun& run) : run_(run) {}
  void heading(int level, const std::string& text, const std::string& id) {
    md_ += "\n" + std::string(size_t(level), '#') + " " + text + "\n\n";
    html_ +=
        "<h" + std::to_string(level) + " id=\"" + id + "\">" + htmlEscape(text) + "</h" + std::to_string(level) + ">\n";
  }
  void para(const std::string& text, const char* cls = nullptr) {
    md_ += (cls ? "> " : "") + text + "\n\n";
    html_ += std::string("<p") + (cls ? std::string(" class=\"") + cls + "\"" : "") + ">" + htmlEscape(text) + "</p>\n";
  }
  // Every table scrolls inside its own box (the page stays within the window); wide ones pin
  // their first column so a row stays readable while scrolling.
  // Each header links to its definition in the closing "Column definitions" section.
  void table(Table t, const std::string& cls, bool sticky = false) {
    t.headerHrefs.clear();
    for (const std::string& h : t.header) {
      t.headerHrefs.push_back("#" + definitionAnchor(h));
      if (std::find(defined_.begin(), defined_.end(), h) == defined_.end()) defined_.push_back(h);
    }
    md_ += toMarkdown(t) + "\n";
    html_ += "<div class=\"table-wrap\">" + toHtml(t, cls + (sticky ? " sticky" : "")) + "</div>\n";
  }
  // Every column header used above, defined once, in order of first use.
  void glossary() {
    heading(2, "Column definitions", "glossary");
    para(
        "What each table column holds. Timing columns are over the timed frames (every frame of the path at the "
        "config's fps, warm-up excluded, all repetitions); error, image and stability columns over the measured "
        "frames (every measure.every-th frame).");
    std::string html = "<dl class=\"glossary\">";
    for (const std::string& h : defined_) {
      std::string text = columnDefinition(run_, h).value_or("(no definition recorded: a report bug)");
      md_ += "- **" + h + "**: " + text + "\n";
      html += "<dt id=\"" + definitionAnchor(h) + "\">" + htmlEscape(h) + "</dt><dd>" + htmlEscape(text) + "</dd>";
    }
    md_ += "\n";
    html_ += html + "</dl>\n";
  }
  void howto(const std::vector<std::string>& keys) {
    auto [md, html] = howToRead(keys);
    raw(md, html);
  }
  void raw(const std::string& md, const std::string& html) {
    md_ += md;
    html_ += html;
  }
  Page page() const { return {md_, html_}; }

 private:
  const ReportRun& run_;
  std::string md_, html_;
  std::vector<std::string> defined_;
};

void chartBoxes(Writer& w, const std::string& section, const std::vector<Chart>& charts) {
  for (auto& c : charts) {
    if (c.section != section) continue;
    if (!c.note.empty()) {
      w.para(c.note, "note");
      continue;
    }
    w.raw("![" + c.title + "](svg/" + c.id + ".svg)\n\n" + chartFilesMarkdown(c) +
              (c.caption.empty() ? "" : ". " + c.caption) + "\n\n",
          "<figure class=\"chart-box\"><div class=\"chart\" id=\"chart-" + c.id + "\" data-chart=\"" + c.id +
              "\"></div>" + chartFilesHtml(c) +
              (c.caption.empty() ? "" : "<figcaption>" + htmlEscape(c.caption) + "</figcaption>") + "</figure>\n");
  }
}

void chartSection(Writer& w, const Section& s, const std::vector<Chart>& charts) {
  if (std::none_of(charts.begin(), charts.end(), [&](const Chart& c) { return c.section == s.id; }))
    return;  // scale: only when the run varies grid, resolution or a parameter
  w.heading(2, s.title, s.id);
  w.para(s.intro);
  chartBoxes(w, s.id, charts);
}

// A matched run (config "match"): every scheme's cost at the one error it was matched to.
void equalErrorPart(Writer& w, const ReportRun& run, const std::vector<Chart>& charts) {
  const EqualErrorSection eq = equalErrorSection(run);
  if (!eq.present) return;
  w.heading(2, eq.title, "equal-error");
  w.para(eq.intro);
  if (!eq.caveat.empty()) w.para(eq.caveat, "caveat");
  w.table(eq.table, "equal-error", true);
  if (!eq.energy.empty()) w.para(eq.energy);
  chartBoxes(w, "equal-error", charts);
}

// The run's verdict.json (`lodbench verdict`, written before the report by `lodbench report`):
// the ranking with intervals, where it holds and where it flips, "no verdict" where they overlap.
void verdictPart(Writer& w, const ReportRun& run) {
  const std::filesystem::path file = std::filesystem::path(run.dir) / "verdict.json";
  std::ifstream in(file);
  if (!in) return;
  nlohmann::json v = nlohmann::json::parse(in, nullptr, false);
  if (v.is_discarded() || !v.contains("schemes") || !v.contains("workloads")) return;
  w.heading(2, "Verdict", "verdict");
  const double conf = v.value("confidence", 0.95);
  auto fmt = [](const nlohmann::json& x) { return x.is_number() ? formatValue(x.get<double>()) : std::string("–"); };
  w.para(
      "Each scheme's cost as a ratio to each workload's cheapest (terrain x path x resolution), its geometric mean "
      "over the workloads it ran with a " +
      formatValue(100 * conf) +
      " % interval, and the workloads it wins (cheapest, every other interval above 1) or ties (intervals "
      "overlapping: no verdict). Method: " +
      v.value("method", std::string("")) + "." +
      (v.value("margin", 0.0) > 0 ? " Margin of practical significance: " + formatValue(100 * v.value("margin", 0.0)) +
                                        " % (a scheme whose interval reaches within it of the cheapest ties)."
                                  : std::string(" No margin of practical significance: a difference that the "
                                                "intervals separate wins, however small (`lodbench verdict "
                                                "--margin` states one).")));
  Table t;
  t.header = {"scheme", "geometric-mean ratio", "interval", "workloads", "wins", "ties", "missing in"};
  t.numeric = {false, true, false, true, true, true, true};
  for (const auto& s : v["schemes"]) {
    const nlohmann::json& g = s["geomean_ratio"];
    std::string interval = g.is_object() && g["lo"].is_number() ? "[" + fmt(g["lo"]) + ", " + fmt(g["hi"]) + "]" : "–";
    t.rows.push_back({textCell(s.value("scheme", std::string("?"))), textCell(g.is_object() ? fmt(g["value"]) : "–"),
                      textCell(interval), textCell(std::to_string(s.value("workloads", 0))),
                      textCell(std::to_string(s.value("wins", 0))), textCell(std::to_string(s.value("ties", 0))),
                      textCell(std::to_string(s["missing_in"].size()))});
  }
  w.table(t, "verdict", true);
  std::string where;
  for (const auto& wl : v["workloads"]) {
    const std::string verdict = wl.value("verdict", std::string(""));
    where += wl.value("id", std::string("?")) + ": " +
             (verdict == "no verdict"      ? "no verdict (" + std::to_string(wl["tied"].size()) + " schemes tie)"
              : verdict == "no scheme ran" ? verdict
                                           : verdict + " wins") +
             "; ";
  }
  if (!where.empty()) w.para("By workload: " + where.substr(0, where.size() - 2) + ".");
}

// Scenario runs (configs/scenarios/): what failure to look for, a grid of how badly each
// scheme shows it, and each case's figure for it with its worst frame.
void scenarioSection(Writer& w, const ReportRun& run, const std::string& runHref) {
  const std::string d = scenarioDescription(run);
  if (d.empty()) return;
  w.heading(2, "Scenario", "scenario");
  w.para("What to look for: " + d);
  const std::string metric = scenarioMetric(d);
  if (metric.empty()) {
    w.para("The description names no per-frame metric after \"Shows in\", so there is no grid.", "note");
    return;
  }
  w.para("Summary grid, " + metric + " by scenario and scheme. " + scenarioGridRule(metric));
  w.table(scenarioGrid(run, metric), "grid", true);
  for (const std::string& o : scenarioOutcomes(run, metric)) w.para("Observed, " + o);
  w.para("One row per case: " + metric +
         " over its measured frames, the frame where it is worst, and that frame's "
         "images.");
  w.table(scenarioTable(run, metric, runHref), "scenario", true);
}

}  // namespace

Page buildPage(const ReportRun& run, const std::vector<Chart>& charts, const std::vector<Strip>& strips,
               const std::string& runHref, const std::vector<std::string>& notes) {
  Writer w(run);
  w.raw("# lodbench report: " + run.name + "\n\n",
        pageAssetsHtml() + "<h1>lodbench report: " + htmlEscape(run.name) + "</h1>\n");
  // The answer first: what the run says, with its thresholds and caveat, then the evidence.
  const std::vector<std::string> answer = openingAnswer(run);
  for (size_t i = 0; i < answer.size(); ++i)
    w.para(answer[i], i + 1 < answer.size() || answer.size() == 1 ? "answer" : "caveat");
  w.para("Run directory " + run.dir + ", " + std::to_string(run.cases.size()) + " cases; report written " +
         isoTimeUtc() + ".");
  for (auto& n : notes) w.para(n, "note");
  verdictPart(w, run);

  w.heading(2, "Context", "context");
  w.table(contextTable(run), "context");
  if (run.context.contains("config")) {
    std::string config = run.context["config"].dump(2);
    w.raw("<details><summary>Config as run</summary>\n\n```json\n" + config + "\n```\n\n</details>\n\n",
          "<details><summary>Config as run</summary><pre>" + htmlEscape(config) + "</pre></details>\n");
  }

  equalErrorPart(w, run, charts);
  for (const Section& s : kChartSections) chartSection(w, s, charts);
  auto [sideMd, sideHtml] = sideBySideSection(run, runHref);
  w.raw(sideMd, sideHtml);

  w.heading(2, "Stability", "stability");
  w.para(
      "Per scheme and path, the worst case of each: cracks (analytic: shared patch edges whose tessellation "
      "factors differ; pixels: background showing through the terrain), popping (mean and p99 absolute RGB "
      "difference, 0-255, between a frame rendered with the previous frame's LOD and with the live LOD), and the "
      "share of measured frames where a visible patch hit factor 64. Links go to the worst frame's images.");
  w.howto({"cracks", "popping", "saturated", "surplus"});
  w.table(stabilityTable(run, runHref), "stability", true);
  scenarioSection(w, run, runHref);

  w.heading(2, "Failed and skipped cases", "problems");
  Table problems = problemTable(run);
  if (problems.rows.empty())
    w.para("None: every case ran.");
  else
    w.table(problems, "problems");

  // Clock control: cases whose calibration workload drifted over the timed frames, and GPU cases
  // that did not calibrate at all (their clock may have been anywhere).
  std::string flagged, uncontrolled;
  int calibrated = 0;
  for (const ReportCase& c : run.cases) {
    auto cal = c.summary.find("calibration");
    if (cal == c.summary.end() || !cal->is_object()) continue;
    if (!cal->value("controlled", true)) {
      if (cal->value("flagged", false)) uncontrolled += (uncontrolled.empty() ? "" : ", ") + c.id;
      continue;
    }
    ++calibrated;
    if (cal->value("flagged", false)) {
      auto d = cal->find("drift");
      char pct[32] = "unknown";
      if (d != cal->end() && d->is_number()) std::snprintf(pct, sizeof pct, "%+.1f%%", d->get<double>() * 100);
      flagged += (flagged.empty() ? "" : ", ") + c.id + " (" + pct + ")";
    }
  }
  if (calibrated > 0)
    w.para(flagged.empty()
               ? "Clock control: no case's calibration drifted by more than 2% over its timed frames."
               : "Clock control: calibration drifted by more than 2% over the timed frames of " + flagged + ".",
           "note");
  if (!uncontrolled.empty())
    w.para(
        "Clock not controlled (calibration turned off on a GPU, so these timings may come from any clock "
        "between idle and boost): " +
            uncontrolled + ".",
        "caveat");

  if (Table memory = memoryTable(run); !memory.rows.empty()) {
    w.heading(2, "Memory", "memory");
    w.para(
        "Device memory each case's renderer held at its end, by resource, as the device sized each allocation: "
        "the terrain's heights and shading normal map (with its mips), the scheme's tables, its geometry (patch "
        "grid or footprint meshes, patch bounds), instance records, LOD state kept across frames, and the frame "
        "(render targets, uniforms). \"of it LOD\" is tables, geometry, instances and LOD state: what the scheme "
        "adds over what every scheme holds. Capture buffers (measurement read-backs) are counted apart, outside "
        "the total; driver-internal memory is not seen. Host peak: the process's peak resident set during the "
        "case.");
    w.table(memory, "memory", true);
  }

  w.heading(2, "Every case", "cases");
  std::vector<std::string> omitted;
  Table cases = caseTable(run, omitted);
  w.para(
      "Timing statistics over timed frames; error, image and stability metrics are means (cracks: maximum) over "
      "measured frames. – marks a metric the case does not have.");
  std::vector<std::string> notesFor;
  for (auto& [key, header] : std::vector<std::pair<std::string, std::string>>{{"gpu", "GPU ms median"},
                                                                              {"triangles", "triangles median"},
                                                                              {"error", "error mean px"},
                                                                              {"psnr", "PSNR dB"},
                                                                              {"ssim", "SSIM"},
                                                                              {"flip", "FLIP mean"},
                                                                              {"cracks", "cracks px max"},
                                                                              {"popping", "popping mean"},
                                                                              {"surplus", "surplus"}})
    if (std::count(cases.header.begin(), cases.header.end(), header)) notesFor.push_back(key);
  w.howto(notesFor);
  w.table(cases, "cases", true);
  if (!omitted.empty()) {
    std::string list;
    for (auto& o : omitted) list += (list.empty() ? "" : ", ") + o;
    w.para("Columns left out, no case has them: " + list + ".", "note");
  }

  auto [imagesMd, imagesHtml] = imageSection(run, strips, runHref);
  w.raw(imagesMd, imagesHtml);
  w.glossary();
  return w.page();
}

}  // namespace lb
