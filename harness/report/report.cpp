#include "report/report.h"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "report/charts.h"
#include "report/equal_error.h"
#include "report/report_howto.h"
#include "report/report_page.h"
#include "report/run_data.h"
#include "report/scenario_summary.h"
#include "report/scenario_table.h"
#include "results/write.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

// Files a previous report wrote that this one may not (a chart left out now): only our own kinds.
void removeStale(const fs::path& dir, const std::string& suffix) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  for (auto& e : fs::directory_iterator(dir, ec)) {
    std::string name = e.path().filename().string();
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      fs::remove(e.path(), ec);
  }
}

// The run directory as the report links to it: relative while the report lies inside the run
// (the default <run>/report, so the pair can move together), absolute otherwise.
std::string runHrefFrom(const fs::path& out, const std::string& runDir) {
  std::error_code ec;
  fs::path rel = fs::relative(fs::absolute(runDir), fs::absolute(out), ec);
  bool inside = !ec && !rel.empty();
  for (auto& part : rel) inside = inside && part == "..";
  return inside ? rel.generic_string() : fs::absolute(runDir).lexically_normal().string();
}

}  // namespace

ReportOutput writeReport(const ReportOptions& options) {
  // The folder of a scenario sweep (scripts/run-scenarios.sh OUT): one summary over its runs.
  if (isRunCollection(options.runDir)) return writeScenarioSummary(options);
  ReportRun run = loadReportRun(options.runDir);
  fs::path out = options.outDir.empty() ? fs::path(options.runDir) / "report" : fs::path(options.outDir);
  fs::create_directories(out / "charts");
  fs::create_directories(out / "data");
  removeStale(out / "charts", ".vl.json");
  removeStale(out / "data", ".json");
  removeStale(out / "svg", ".svg");
  removeStale(out / "png", ".png");

  std::vector<Chart> charts = speedCharts(run);
  for (auto& c : scaleCharts(run)) charts.push_back(std::move(c));
  charts.push_back(histogramChart(run));
  for (auto& c : timelineCharts(run)) charts.push_back(std::move(c));
  if (EqualErrorSection eq = equalErrorSection(run); eq.present) charts.push_back(std::move(eq.chart));

  ReportOutput result;
  result.dir = out.string();
  result.notes = run.notes;
  json manifest = {{"title", "lodbench report: " + run.name},
                   {"run_dir", run.dir},
                   {"charts", json::array()},
                   {"omitted", json::array()}};
  std::set<std::string> written;
  for (auto& c : charts) {
    if (!c.note.empty()) {
      result.omittedCharts++;
      result.notes.push_back(c.note);
      manifest["omitted"].push_back({{"id", c.id}, {"note", c.note}});
      continue;
    }
    result.charts++;
    writeFileAtomic((out / "charts" / (c.id + ".vl.json")).string(), c.spec.dump(2) + "\n");
    if (written.insert(c.dataName).second)  // the timelines share one data file
      writeFileAtomic((out / "data" / (c.dataName + ".json")).string(), c.data.dump() + "\n");
    manifest["charts"].push_back(
        {{"id", c.id}, {"title", c.title}, {"section", c.section}, {"spec", "charts/" + c.id + ".vl.json"}});
  }

  std::string runHref = runHrefFrom(out, options.runDir);
  std::vector<std::string> pageNotes = run.notes;
  std::vector<Strip> strips = imageStrips(run, options.frames, scenarioMetric(scenarioDescription(run)), pageNotes);
  for (size_t i = run.notes.size(); i < pageNotes.size(); ++i) result.notes.push_back(pageNotes[i]);
  Page page = buildPage(run, charts, strips, runHref, pageNotes);
  writeFileAtomic((out / "report.md").string(), page.markdown);
  writeFileAtomic((out / "body.html").string(), page.html);
  writeFileAtomic((out / "manifest.json").string(), manifest.dump(2) + "\n");
  // The metric notes link here: a copy of the definitions, so the link works wherever the folder goes.
  const fs::path doc = fs::path(LODBENCH_SOURCE_DIR) / "docs/results-format.md";
  std::error_code ec;
  if (fs::is_regular_file(doc, ec)) fs::copy_file(doc, out / kFormatDocName, fs::copy_options::overwrite_existing, ec);
  if (ec || !fs::is_regular_file(out / kFormatDocName))
    result.notes.push_back(std::string(kFormatDocName) + " not copied from " + doc.string() +
                           (ec ? ": " + ec.message() : ": missing") + "; the metric notes' links will not resolve.");
  return result;
}

std::string reportScriptDir() {
  const char* env = std::getenv("LODBENCH_REPORT_JS");
  return env && *env ? env : std::string(LODBENCH_SOURCE_DIR) + "/report";
}

std::string renderUnavailableReason() {
  std::error_code ec;
  if (std::system("command -v node >/dev/null 2>&1") != 0) return "node is not installed";
  fs::path dir = reportScriptDir();
  if (!fs::is_regular_file(dir / "render.mjs", ec)) return (dir / "render.mjs").string() + " is missing";
  if (!fs::is_directory(dir / "node_modules" / "vega-lite", ec))
    return (dir / "node_modules").string() + " is missing (npm ci has not run)";
  return "";
}

int renderHtml(const std::string& reportDir, bool selfContained) {
  std::string cmd = "node " + shellQuote(reportScriptDir() + "/render.mjs") + " " + shellQuote(reportDir) +
                    (selfContained ? " --self-contained" : "");
  int status = std::system(cmd.c_str());
  return status == -1 ? 1 : WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

int reportCommand(const ReportOptions& options) {
  ReportOutput r = writeReport(options);
  for (auto& n : r.notes) std::fprintf(stderr, "lodbench: note: %s\n", n.c_str());
  std::fprintf(stderr, "lodbench: %s/report.md and %d chart specs written (%d left out)\n", r.dir.c_str(), r.charts,
               r.omittedCharts);
  if (!options.html) return 0;
  std::string why = renderUnavailableReason();
  if (!why.empty()) {
    std::fprintf(stderr,
                 "lodbench: report.html not rendered: %s.\n"
                 "  Set up the report renderer once with: bash scripts/install-report-deps.sh\n"
                 "  then render with: node report/render.mjs %s\n",
                 why.c_str(), r.dir.c_str());
    return 0;
  }
  int rc = renderHtml(r.dir, options.selfContained);
  if (rc != 0) {
    std::fprintf(stderr, "lodbench: report/render.mjs failed (exit %d)\n", rc);
    return 1;
  }
  std::error_code ec;
  auto bytes = fs::file_size(fs::path(r.dir) / "report.html", ec);
  if (!ec)
    std::fprintf(stderr, "lodbench: report.html is %.1f MB (%ju bytes)%s\n", double(bytes) / 1e6, uintmax_t(bytes),
                 options.selfContained ? ", self-contained (images embedded)" : "; it links the run's images/");
  std::printf("%s/report.html\n", r.dir.c_str());
  return 0;
}

}  // namespace lb
