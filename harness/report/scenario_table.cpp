#include "report/scenario_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "report/page_assets.h"
#include "report/report_tables.h"

namespace lb {

namespace {

// "triangles" is the per-frame clip_primitives counter (primitives that reached clipping).
std::string frameKey(const std::string& metric) {
  return metric == "triangles" ? "clip_primitives" : metric;
}

struct CaseMetric {
  std::optional<double> mean, worst;
  int worstFrame = -1;
};

CaseMetric caseMetric(const ReportCase& c, const std::string& metric) {
  const std::string key = frameKey(metric);
  const bool lowerIsWorse = higherIsBetter(metric);
  CaseMetric m;
  double sum = 0;
  int n = 0;
  for (const auto& f : c.frames) {
    auto v = frameValue(f, key);
    if (!v) continue;
    sum += *v, ++n;
    if (!m.worst || (lowerIsWorse ? *v < *m.worst : *v > *m.worst)) {
      m.worst = v;
      m.worstFrame = f.value("frame", -1);
    }
  }
  if (n) m.mean = sum / n;
  return m;
}

// White (best) to dark red (worst), linear in badness; text turns white on the dark end.
std::string badnessStyle(double b) {
  auto mix = [&](int from, int to) { return int(std::lround(from + (to - from) * b)); };
  char buf[96];
  std::snprintf(buf, sizeof buf, "style=\"background:#%02x%02x%02x;color:%s\"", mix(255, 165), mix(255, 0),
                mix(255, 38), b > 0.6 ? "#fff" : "#222");
  return buf;
}

}  // namespace

std::string scenarioDescription(const ReportRun& run) {
  if (run.name.rfind("scenario-", 0) != 0 || !run.context.contains("config")) return "";
  const auto& config = run.context["config"];
  auto it = config.find("description");
  return it != config.end() && it->is_string() ? it->get<std::string>() : "";
}

std::string scenarioMetric(const std::string& description) {
  static const char* const kMetrics[] = {"saturated_patches", "err_mean_px",   "err_p95_px", "err_max_px",
                                         "cracks_analytic",   "cracks_pixels", "pop_mean",   "pop_changed",
                                         "img_frac_over",     "img_psnr_db",   "img_ssim",   "triangles"};
  const size_t from = description.find("Shows in");
  if (from == std::string::npos) return "";
  size_t best = std::string::npos;
  std::string metric;
  for (const char* m : kMetrics) {
    const size_t at = description.find(m, from);
    if (at < best) best = at, metric = m;
  }
  return metric;
}

bool higherIsBetter(const std::string& metric) {
  return metric == "img_psnr_db" || metric == "img_ssim";
}

double badness(double value, double best, double worst) {
  const double span = std::fabs(worst - best);
  return span > 0 ? std::min(1.0, std::fabs(value - best) / span) : 0.0;
}

std::string scenarioGridRule(const std::string& metric) {
  return std::string("Each cell: the case's mean of ") + metric +
         " over its measured frames. Colour, per scenario row: 0 (white) = the best case on that scenario (" +
         (higherIsBetter(metric) ? "highest" : "lowest") +
         "), 1 (dark red) = the worst, linear in between: (value - best) / (worst - best); the Markdown shows this "
         "score in brackets. A row where every case is equal stays white. A cell links to the case's row in the "
         "scenario's table. Scenarios "
         "read as a difference from a control (e.g. far-origin against the terrain at the origin) show the signed "
         "difference from the control row's value for the same scheme and parameters, scored on its size.";
}

int scenarioWorstFrame(const ReportCase& c, const std::string& metric) {
  return caseMetric(c, metric).worstFrame;
}

std::string scenarioRowId(const std::string& caseId) {
  return "scn-" + caseId;
}

std::vector<std::string> gridColumns(const std::vector<const ReportRun*>& runs) {
  std::vector<std::string> columns;  // scheme + parameters, in case order
  for (const ReportRun* run : runs)
    for (const ReportCase& c : run->cases)
      if (std::find(columns.begin(), columns.end(), c.label) == columns.end()) columns.push_back(c.label);
  return columns;
}

std::string controlScenario(const ReportRun& run) {
  const std::string d = scenarioDescription(run);
  if (d.find("difference from the") == std::string::npos || run.scenarios.size() < 2) return "";
  for (const std::string& s : run.scenarios)
    if (std::all_of(run.scenarios.begin(), run.scenarios.end(),
                    [&](const std::string& o) { return o.rfind(s, 0) == 0; }))
      return s;
  return "";
}

namespace {

// The cells of one scenario row. With `control` (label -> the control row's mean), a cell holds the
// signed difference from the control and is scored on its size; the control row itself is plain.
std::vector<Cell> rowCells(const std::vector<const ReportCase*>& cases, const std::vector<std::string>& columns,
                           const std::string& metric, const std::string& mdPrefix, const std::string& htmlPrefix,
                           const std::map<std::string, double>* control, bool isControl) {
  std::map<std::string, std::pair<const ReportCase*, std::optional<double>>> byLabel;
  std::optional<double> best, worst;
  const bool up = higherIsBetter(metric) && !control;
  for (const ReportCase* c : cases) {
    std::optional<double> v = c->status == "ok" ? caseMetric(*c, metric).mean : std::nullopt;
    if (v && control && !isControl) {
      auto ctl = control->find(c->label);
      v = ctl == control->end() ? std::nullopt : std::optional<double>(*v - ctl->second);
    }
    byLabel[c->label] = {c, v};
    if (!v) continue;
    const double score = control ? std::fabs(*v) : *v;
    if (!best || (up ? score > *best : score < *best)) best = score;
    if (!worst || (up ? score < *worst : score > *worst)) worst = score;
  }
  std::vector<Cell> row;
  for (auto& col : columns) {
    auto it = byLabel.find(col);
    if (it == byLabel.end()) {
      row.push_back(textCell(""));  // this scheme and parameters did not run on this scenario
      continue;
    }
    const auto& [c, v] = it->second;
    if (!v) {
      row.push_back(c->status == "ok" ? textCell("–") : textCell(c->status));
      continue;
    }
    const std::string shown = (control && !isControl && *v > 0 ? "+" : "") + formatValue(*v);
    Cell cell = linkCell(shown, mdPrefix + "#" + scenarioRowId(c->id), htmlPrefix + "#" + scenarioRowId(c->id));
    if (!isControl) {
      const double b = badness(control ? std::fabs(*v) : *v, *best, *worst);
      char score[16];
      std::snprintf(score, sizeof score, "%.2f", b);
      cell.md = shown + " [" + score + "]";
      cell.tdAttrs =
          badnessStyle(b) + " title=\"" + htmlEscape(c->label) + ": " + score + "\" data-badness=\"" + score + "\"";
    }
    row.push_back(cell);
  }
  return row;
}

// The control row's mean of `metric` per scheme-and-parameters label ({} without a control row).
std::map<std::string, double> controlMeans(const ReportRun& run, const std::string& controlRow,
                                           const std::string& metric) {
  std::map<std::string, double> control;
  for (const ReportCase& c : run.cases)
    if (!controlRow.empty() && c.scenario == controlRow && c.status == "ok")
      if (auto v = caseMetric(c, metric).mean) control[c.label] = *v;
  return control;
}

}  // namespace

std::vector<std::pair<std::string, std::vector<Cell>>> gridRows(const ReportRun& run,
                                                                const std::vector<std::string>& columns,
                                                                const std::string& metric, const std::string& mdPrefix,
                                                                const std::string& htmlPrefix) {
  const std::string controlRow = controlScenario(run);
  auto casesOf = [&](const std::string& scenario) {
    std::vector<const ReportCase*> cases;
    for (const ReportCase& c : run.cases)
      if (c.scenario == scenario) cases.push_back(&c);
    return cases;
  };
  const std::map<std::string, double> control = controlMeans(run, controlRow, metric);
  std::vector<std::pair<std::string, std::vector<Cell>>> rows;
  for (const std::string& scenario : run.scenarios) {
    const bool isControl = !controlRow.empty() && scenario == controlRow;
    rows.emplace_back(scenario + (isControl            ? " (control)"
                                  : controlRow.empty() ? ""
                                                       : " (difference)"),
                      rowCells(casesOf(scenario), columns, metric, mdPrefix, htmlPrefix,
                               controlRow.empty() ? nullptr : &control, isControl));
  }
  return rows;
}

std::vector<std::string> scenarioOutcomes(const ReportRun& run, const std::string& metric) {
  const std::string controlRow = controlScenario(run);
  const std::map<std::string, double> control = controlMeans(run, controlRow, metric);
  const bool up = higherIsBetter(metric) && controlRow.empty();
  std::vector<std::string> out;
  for (const std::string& scenario : run.scenarios) {
    if (!controlRow.empty() && scenario == controlRow) continue;
    std::vector<std::pair<std::string, double>> values;  // label, value (difference from the control)
    for (const ReportCase& c : run.cases) {
      if (c.scenario != scenario || c.status != "ok") continue;
      std::optional<double> v = caseMetric(c, metric).mean;
      if (v && !controlRow.empty()) {
        auto ctl = control.find(c.label);
        v = ctl == control.end() ? std::nullopt : std::optional<double>(*v - ctl->second);
      }
      if (v) values.emplace_back(c.label, *v);
    }
    const std::string what = controlRow.empty() ? metric : metric + " minus the control's";
    std::string line = scenario + ": ";
    if (values.empty()) {
      out.push_back(line + "no finished case has " + metric + ".");
      continue;
    }
    auto score = [&](double v) { return controlRow.empty() ? (up ? -v : v) : std::fabs(v); };
    auto shown = [&](double v) { return (!controlRow.empty() && v > 0 ? "+" : "") + formatValue(v); };
    auto [lo, hi] = std::minmax_element(values.begin(), values.end(),
                                        [&](auto& a, auto& b) { return score(a.second) < score(b.second); });
    const double span = std::fabs(hi->second - lo->second), scale = std::max(1.0, std::fabs(hi->second));
    if (span <= 1e-9 * scale)
      line += "every case reads " + shown(values[0].second) + " on " + what +
              ": the predicted failure did not appear here.";
    else
      line += "worst " + hi->first + " (" + shown(hi->second) + "), best " + lo->first + " (" + shown(lo->second) +
              ") on " + what + ".";
    out.push_back(line);
  }
  return out;
}

Table scenarioGrid(const ReportRun& run, const std::string& metric) {
  const std::vector<std::string> columns = gridColumns({&run});
  Table t{{"scenario"}, {}, {false}};
  for (auto& col : columns) {
    t.header.push_back(col);
    t.numeric.push_back(true);
  }
  for (auto& [label, cells] : gridRows(run, columns, metric, "", "")) {
    std::vector<Cell> row{textCell(label)};
    for (Cell& cell : cells) row.push_back(std::move(cell));
    t.rows.push_back(std::move(row));
  }
  return t;
}

Table scenarioTable(const ReportRun& run, const std::string& metric, const std::string& runHref) {
  Table t{{"scheme", "parameters", "path / terrain", metric + " mean", metric + " worst", "worst frame", "images"},
          {},
          {false, false, false, true, true, true, false}};
  for (const ReportCase& c : run.cases) {
    if (c.status != "ok") continue;
    const CaseMetric m = caseMetric(c, metric);
    std::vector<Cell> links;
    auto imgs = run.images.find(c.id);
    if (imgs != run.images.end() && imgs->second.count(m.worstFrame))
      for (auto& [mode, file] : imgs->second.at(m.worstFrame))
        links.push_back(linkCell(mode, runHref + "/" + file, "#" + imageAnchor(c.id, m.worstFrame)));
    Cell images = links.empty() ? textCell("–") : joinCells(links, ", ", ", ");
    if (links.empty() && m.worstFrame >= 0) images = missingImageCell(c.id, m.worstFrame);
    t.rows.push_back({schemeCell(run, c.scheme), textCell(c.paramsLabel), textCell(c.scenario),
                      textCell(formatValue(m.mean)), textCell(formatValue(m.worst)),
                      textCell(m.worstFrame >= 0 ? std::to_string(m.worstFrame) : "–"), images});
    t.rowIds.push_back(scenarioRowId(c.id));
  }
  return t;
}

}  // namespace lb
