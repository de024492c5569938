#include "report/scenario_summary.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "error.h"
#include "report/page_assets.h"
#include "report/run_data.h"
#include "report/scenario_table.h"
#include "report/table.h"
#include "results/write.h"

namespace lb {

namespace fs = std::filesystem;

namespace {

bool isRunDir(const fs::path& d) {
  std::error_code ec;
  return fs::is_regular_file(d / "summary.json", ec) || fs::is_directory(d / "cases", ec);
}

}  // namespace

bool isRunCollection(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec) || isRunDir(dir)) return false;
  for (auto& e : fs::directory_iterator(dir, ec))
    if (e.is_directory() && isRunDir(e.path())) return true;
  return false;
}

ReportOutput writeScenarioSummary(const ReportOptions& options) {
  const fs::path root(options.runDir);
  const fs::path out = options.outDir.empty() ? root / "report" : fs::path(options.outDir);
  ReportOutput result;
  result.dir = out.string();
  std::vector<fs::path> dirs;
  for (auto& e : fs::directory_iterator(root))
    if (e.is_directory() && isRunDir(e.path())) dirs.push_back(e.path());
  std::sort(dirs.begin(), dirs.end());
  std::vector<std::unique_ptr<ReportRun>> runs;
  for (auto& d : dirs) {
    auto run = std::make_unique<ReportRun>(loadReportRun(d.string()));
    if (scenarioDescription(*run).empty()) {
      result.notes.push_back(d.string() +
                             ": not a scenario run (config name does not start with \"scenario-\"), "
                             "left out of the summary");
      continue;
    }
    runs.push_back(std::move(run));
  }
  if (runs.empty())
    throw InputError(options.runDir + ": no scenario runs in this folder (scripts/run-scenarios.sh OUT)");

  std::vector<const ReportRun*> all;
  for (auto& r : runs) all.push_back(r.get());
  const std::vector<std::string> columns = gridColumns(all);
  Table grid{{"scenario", "metric"}, {}, {false, false}};
  for (auto& col : columns) {
    grid.header.push_back(col);
    grid.numeric.push_back(true);
  }
  std::string md, html, list;
  std::string mdList;
  for (const ReportRun* run : all) {
    const std::string name = run->name.substr(std::string("scenario-").size());
    const std::string description = scenarioDescription(*run), metric = scenarioMetric(description);
    std::error_code ec;
    const fs::path runReport = fs::path(run->dir) / "report";
    const std::string rel = fs::relative(runReport, out, ec).generic_string();
    const bool hasReport = !ec && fs::is_regular_file(runReport / "report.html");
    if (!hasReport)
      result.notes.push_back(run->dir + ": no report.html (run `lodbench report " + run->dir + "`): grid links dangle");
    for (auto& [scenario, cells] : gridRows(*run, columns, metric, rel + "/report.md", rel + "/report.html")) {
      const std::string label = name + (run->scenarios.size() > 1 ? " / " + scenario : "");
      std::vector<Cell> row{linkCell(label, rel + "/report.md", "#about-" + name),
                            codeCell(metric.empty() ? "–" : metric)};
      if (metric.empty())
        for (size_t i = 0; i < columns.size(); ++i) row.push_back(textCell(i ? "" : "(no metric named)"));
      else
        for (Cell& cell : cells) row.push_back(std::move(cell));
      grid.rows.push_back(std::move(row));
    }
    std::string observed;
    if (!metric.empty())
      for (const std::string& o : scenarioOutcomes(*run, metric)) observed += (observed.empty() ? "" : " ") + o;
    if (!observed.empty()) observed = " Observed: " + observed;
    mdList += "- **" + name + "** ([report](" + rel + "/report.md)): " + description + observed + "\n";
    list += "<li id=\"about-" + htmlEscape(name) + "\"><b>" + htmlEscape(name) + "</b> (<a href=\"" +
            htmlEscape(rel + "/report.html") + "\">report</a>): " + htmlEscape(description) +
            (observed.empty() ? "" : "<br><i>" + htmlEscape(observed.substr(1)) + "</i>") + "</li>\n";
  }
  const std::string title = "lodbench scenarios: " + fs::absolute(root).lexically_normal().filename().string();
  const std::string intro = std::to_string(all.size()) + " scenario runs in " + options.runDir + "; report written " +
                            isoTimeUtc() +
                            ". Each scenario provokes one failure a seed "
                            "predicts and names the metric that shows it.";
  const std::string rule = scenarioGridRule("the scenario's metric") +
                           " Columns are scheme and parameters; an empty cell: not run on that scenario.";
  md = "# " + title + "\n\n" + intro + "\n\n## Summary grid\n\n" + rule + "\n\n" + toMarkdown(grid) +
       "\n## What each scenario shows\n\n" + mdList;
  html = pageAssetsHtml() + "<h1>" + htmlEscape(title) + "</h1>\n<p>" + htmlEscape(intro) + "</p>\n" +
         "<h2 id=\"grid\">Summary grid</h2>\n<p>" + htmlEscape(rule) + "</p>\n<div class=\"table-wrap\">" +
         toHtml(grid, "grid sticky") + "</div>\n<h2 id=\"scenarios\">What each scenario shows</h2>\n<ul>\n" + list +
         "</ul>\n";
  fs::create_directories(out);
  writeFileAtomic((out / "report.md").string(), md);
  writeFileAtomic((out / "body.html").string(), html);
  nlohmann::json manifest = {{"title", title},
                             {"run_dir", options.runDir},
                             {"charts", nlohmann::json::array()},
                             {"omitted", nlohmann::json::array()}};
  writeFileAtomic((out / "manifest.json").string(), manifest.dump(2) + "\n");
  return result;
}

}  // namespace lb
