#include "report/scenario_table.h"

#include <algorithm>

#include "report/report_tables.h"

namespace lb {

std::string scenarioDescription(const ReportRun& run) {
  if (run.name.rfind("scenario-", 0) != 0 || !run.context.contains("config")) return "";
  const auto& config = run.context["config"];
  auto it = config.find("description");
  return it != config.end() && it->is_string() ? it->get<std::string>() : "";
}

std::string scenarioMetric(const std::string& description) {
  static const char* const kMetrics[] = {"saturated_patches", "err_mean_px", "err_p95_px",   "err_max_px",
                                         "cracks_analytic",   "cracks_pixels", "pop_mean",   "pop_changed",
                                         "img_frac_over",     "img_psnr_db",   "triangles"};
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

Table scenarioTable(const ReportRun& run, const std::string& metric, const std::string& runHref) {
  // "triangles" is the per-frame clip_primitives counter (primitives that reached clipping).
  const std::string key = metric == "triangles" ? "clip_primitives" : metric;
  const bool lowerIsWorse = metric == "img_psnr_db";
  Table t{{"scheme", "parameters", "path / terrain", metric + " mean", metric + " worst", "worst frame", "images"},
          {},
          {false, false, false, true, true, true, false}};
  for (const ReportCase& c : run.cases) {
    if (c.status != "ok") continue;
    double sum = 0;
    int n = 0, worstFrame = -1;
    std::optional<double> worst;
    for (const auto& f : c.frames) {
      auto v = frameValue(f, key);
      if (!v) continue;
      sum += *v, ++n;
      if (!worst || (lowerIsWorse ? *v < *worst : *v > *worst)) {
        worst = v;
        worstFrame = f.value("frame", -1);
      }
    }
    std::vector<Cell> links;
    auto imgs = run.images.find(c.id);
    if (imgs != run.images.end() && imgs->second.count(worstFrame))
      for (auto& [mode, file] : imgs->second.at(worstFrame))
        links.push_back(linkCell(mode, runHref + "/" + file, "#" + imageAnchor(c.id, worstFrame)));
    t.rows.push_back({textCell(c.scheme), textCell(c.paramsLabel), textCell(c.scenario),
                      textCell(formatValue(n ? std::optional<double>(sum / n) : std::nullopt)),
                      textCell(formatValue(worst)), textCell(worstFrame >= 0 ? std::to_string(worstFrame) : "–"),
                      links.empty() ? textCell(worstFrame >= 0 ? "(no image of that frame)" : "–")
                                    : joinCells(links, ", ", ", ")});
  }
  return t;
}

}  // namespace lb
