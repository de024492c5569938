#include "report/report_tables.h"

#include <algorithm>
#include <cstdio>

#include "metrics/coverage.h"
#include "report/page_assets.h"
#include "schemes/registry.h"

namespace lb {

using nlohmann::json;

namespace {

std::string text(const json& obj, const char* key) {
  auto it = obj.find(key);
  if (it == obj.end() || it->is_null()) return "–";
  return it->is_string() ? it->get<std::string>() : it->dump();
}

std::optional<double> plainNumber(const json& obj, const char* key) {
  auto it = obj.find(key);
  return it != obj.end() && it->is_number() ? std::optional<double>(it->get<double>()) : std::nullopt;
}

// A summary column: summary[key][stat], or summary[key] itself when stat is empty.
struct Column {
  const char* header;
  const char* key;
  const char* stat;
  bool optIn = false;  // present only when the config asks for it: not listed as left out
};
constexpr Column kCaseColumns[] = {
    {"frames", "frames", ""},
    {"GPU ms median", "gpu_ms", "median"},
    {"GPU ms p95", "gpu_ms", "p95"},
    {"GPU ms depth", "gpu_ms_depth", "median", true},        // timing modes
    {"GPU ms frontend", "gpu_ms_frontend", "median", true},  // LOD decision + tessellator only
    // Draw paths whose LOD runs apart from drawing (instanced grid): GPU LOD and draw time, and
    // the CPU selection with its upload, which gpu_ms leaves out.
    {"LOD GPU ms", "lod_ms", "median", true},
    {"draw GPU ms", "draw_ms", "median", true},
    {"LOD CPU ms", "lod_cpu_ms", "median", true},
    {"CPU ms median", "cpu_ms", "median"},
    {"harness CPU ms", "cpu_harness_ms", "median", true},     // runs recorded before timing modes lack it
    {"calibration drift", "calibration", "drift", true},      // flagged when |drift| > 0.02
    {"energy J/frame", "energy_j_per_frame", "mean", true},   // boards with an energy counter (NVML)
    {"energy spread", "energy_j_per_frame", "spread", true},  // (max - min) / mean of its rounds
    {"FPS median", "fps_median", ""},
    {"triangles median", "triangles", "median"},
    {"patches median", "patches", "median"},
    {"instances median", "instances", "median", true},
    {"degenerate triangles", "hist_degenerate_total", "", true},
    {"error mean px", "err_mean_px", "mean"},
    {"error p95 px", "err_p95_px", "mean"},
    {"PSNR dB", "img_psnr_db", "mean"},
    {"SSIM", "img_ssim", "mean"},
    {"FLIP mean", "flip_mean", "mean", true},  // runs before FLIP lack these: not listed as left out
    {"FLIP p95", "flip_p95", "mean", true},
    {"cracks px max", "cracks_pixels", "max"},
    {"missing terrain px max", "coverage_missing_px", "max"},
    {"extra terrain px max", "coverage_extra_px", "max"},
    {"popping mean", "pop_mean", "mean"},
    {"popping lag 2", "pop2_mean", "mean", true},
    {"popping lag 3", "pop3_mean", "mean", true},
    {"lag frames", "settle", "frames", true},
    {"surplus", "surplus", "mean"},
    {"measured frames", "measured_frames", ""},
};

std::optional<double> columnValue(const ReportCase& c, const Column& col) {
  return *col.stat ? summaryStat(c.summary, col.key, col.stat) : plainNumber(c.summary, col.key);
}

// The largest value of summary[key][stat] over cases, and the case that has it.
std::pair<std::optional<double>, const ReportCase*> maxOver(const std::vector<const ReportCase*>& cases,
                                                            const char* key, const char* stat) {
  std::optional<double> best;
  const ReportCase* at = nullptr;
  for (auto* c : cases) {
    auto v = *stat ? summaryStat(c->summary, key, stat) : plainNumber(c->summary, key);
    if (v && (!best || *v > *best)) {
      best = v;
      at = c;
    }
  }
  return {best, at};
}

struct Worst {
  const char* key;  // summary metric and worst_frames key
  const char* label;
  std::vector<const char*> modes;  // preferred image modes for this kind of problem
};
const Worst kWorst[] = {{"cracks_pixels", "cracks", {"cracks", "shaded", "wireframe"}},
                        {"pop_mean", "popping", {"shaded", "heatmap"}},
                        {"err_p95_px", "error", {"error", "heatmap", "shaded"}},
                        {"coverage_missing_px", "missing terrain", {"shaded", "error", "heatmap"}}};

Cell worstCell(const ReportRun& run, const std::vector<const ReportCase*>& cases, const std::string& runHref) {
  std::vector<Cell> parts;
  for (const Worst& w : kWorst) {
    auto [value, c] = maxOver(cases, w.key, "max");
    if (!value || *value <= 0 || !c) continue;  // nothing went wrong: no frame to point at
    auto f = c->summary.find("worst_frames");
    if (f == c->summary.end() || !f->is_object() || !(*f)[w.key].is_number_integer()) continue;
    int frame = (*f)[w.key].get<int>();
    std::string label = std::string(w.label) + ": " + c->label + " f" + std::to_string(frame);
    auto imgs = run.images.find(c->id);
    const std::map<std::string, std::string>* modes = nullptr;
    if (imgs != run.images.end() && imgs->second.count(frame)) modes = &imgs->second.at(frame);
    if (!modes) {
      Cell missing = missingImageCell(c->id, frame);
      parts.push_back({label + " " + missing.md, htmlEscape(label) + " " + missing.html});
      continue;
    }
    std::string file = modes->begin()->second;
    for (auto* m : w.modes)
      if (modes->count(m)) {
        file = modes->at(m);
        break;
      }
    parts.push_back(linkCell(label, runHref + "/" + file, "#" + imageAnchor(c->id, frame)));
  }
  return parts.empty() ? textCell("–") : joinCells(parts, "; ", "<br>");
}

}  // namespace

std::string imageAnchor(const std::string& caseId, int frame) {
  return "img-" + caseId + "-f" + std::to_string(frame);
}

Cell missingImageCell(const std::string& caseId, int frame) {
  const std::string text = "(no image of frame " + std::to_string(frame) + ")";
  return {text, "<span class=\"no-image\" data-case=\"" + htmlEscape(caseId) + "\" data-frame=\"" +
                    std::to_string(frame) + "\">" + htmlEscape(text) + "</span>"};
}

std::vector<int> worstFrames(const ReportCase& c) {
  std::vector<int> frames;
  auto f = c.summary.find("worst_frames");
  if (f == c.summary.end() || !f->is_object()) return frames;
  for (const Worst& w : kWorst) {
    auto v = summaryStat(c.summary, w.key, "max");
    if (v && *v > 0 && (*f)[w.key].is_number_integer()) frames.push_back((*f)[w.key].get<int>());
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

std::string worstOf(const ReportCase& c, int frame) {
  std::string s;
  auto f = c.summary.find("worst_frames");
  if (f == c.summary.end() || !f->is_object()) return s;
  for (const Worst& w : kWorst) {
    auto v = summaryStat(c.summary, w.key, "max");
    if (v && *v > 0 && (*f)[w.key] == frame) s += (s.empty() ? "" : ", ") + std::string(w.label);
  }
  return s;
}

// "41.2 ms a frame over 120 frames: surplus 20.1, ray cast 9.3, ..." (most expensive pass first), so a
// reader sees where a measured frame's time goes (run.json measure_costs_ms).
static std::string measureCostsText(const json& c) {
  if (!c.is_object() || !c.contains("passes")) return "no measured frame in this run";
  std::vector<std::pair<double, std::string>> passes;
  for (auto& [pass, ms] : c["passes"].items())
    if (ms.is_number()) passes.emplace_back(ms.get<double>(), pass);
  std::sort(passes.rbegin(), passes.rend());
  char head[96];
  std::snprintf(head, sizeof head,
                "%.1f ms a frame over %d frames (wall time per pass, ms):", c.value("measured_frame", 0.0),
                c.value("frames", 0));
  std::string s = head;
  for (size_t i = 0; i < passes.size(); ++i) {
    char item[64];
    std::string name = passes[i].second;
    std::replace(name.begin(), name.end(), '_', ' ');
    std::snprintf(item, sizeof item, "%s %s %.1f", i ? "," : "", name.c_str(), passes[i].first);
    s += item;
  }
  return s;
}

Table contextTable(const ReportRun& run) {
  const json& x = run.context;
  const json totals = run.run.value("totals", json::object());
  Table t{{"item", "value"}, {}, {}};
  auto row = [&](const std::string& k, const std::string& v) { t.rows.push_back({textCell(k), textCell(v)}); };
  row("config", run.name + " (" + text(x, "config_file") + ")");
  row("device", text(x, "device") + " (vendor " + text(x, "vendor_id") + ", device " + text(x, "device_id") + ")");
  if (x.contains("device_uuid")) {  // which board of the model, where the run recorded it
    std::string power = plainNumber(x, "power_limit_w") ? "power limit " + text(x, "power_limit_w") + " W (enforced " +
                                                              text(x, "power_limit_enforced_w") + " W)"
                                                        : "power limit unknown: " + text(x, "power_limit_reason");
    row("board", "UUID " + text(x, "device_uuid") + ", " + power);
  }
  if (x.contains("energy_tick_ms")) {  // the energy counter and clocks, where the run recorded them
    std::string energy =
        plainNumber(x, "energy_tick_ms")
            ? text(x, "energy_counter") + ", tick " + formatValue(plainNumber(x, "energy_tick_ms")) + " ms as measured"
            : "none: " + text(x, "energy_reason");
    std::string clocks = plainNumber(x, "sm_clock_max_mhz") || plainNumber(x, "sm_clock_mhz")
                             ? "SM " + text(x, "sm_clock_mhz") + " of " + text(x, "sm_clock_max_mhz") +
                                   " MHz, memory " + text(x, "mem_clock_mhz") + " of " + text(x, "mem_clock_max_mhz") +
                                   " MHz at the run's start"
                             : "clocks unknown: " + text(x, "clocks_reason");
    row("energy counter", energy + "; " + clocks);
  }
  row("driver", text(x, "driver") + ", " + text(x, "driver_info") + ", version " + text(x, "driver_version"));
  row("Vulkan API", text(x, "api_version") + ", timestampPeriod " + text(x, "timestamp_period_ns") + " ns");
  row("lodbench",
      text(x, "tool_version") + ", " + text(x, "build_type") + " build, validation " + text(x, "validation"));
  t.rows.push_back({textCell("git commit"), codeCell(text(x, "git_commit"))});
  row("host", text(x, "host"));
  row("time", text(run.run, "start_time") + " to " + text(run.run, "end_time"));
  row("cases", text(totals, "cases") + " (" + text(totals, "ok") + " ok, " + text(totals, "failed") + " failed, " +
                   text(totals, "skipped") + " skipped)");
  row("validation errors", text(run.run, "validation_errors"));
  row("measured frame", measureCostsText(run.run.value("measure_costs_ms", json())));
  return t;
}

Table caseTable(const ReportRun& run, std::vector<std::string>& omitted) {
  std::vector<const Column*> cols;
  for (const Column& col : kCaseColumns) {
    bool any =
        std::any_of(run.cases.begin(), run.cases.end(), [&](auto& c) { return columnValue(c, col).has_value(); });
    if (any)
      cols.push_back(&col);
    else if (!col.optIn)
      omitted.push_back(col.header);
  }
  Table t{{"case", "scheme", "parameters", "path", "status"}, {}, {false, false, false, false, false}};
  for (auto* col : cols) {
    t.header.push_back(col->header);
    t.numeric.push_back(true);
  }
  for (auto& c : run.cases) {
    std::vector<Cell> row{codeCell(c.id), schemeCell(run, c.scheme), textCell(c.paramsLabel), textCell(c.scenario),
                          textCell(c.status)};
    for (auto* col : cols) row.push_back(textCell(formatValue(columnValue(c, *col))));
    t.rows.push_back(std::move(row));
  }
  return t;
}

Table stabilityTable(const ReportRun& run, const std::string& runHref) {
  Table t{{"scheme", "path", "cases ok / failed / skipped", "cracks: edges (max)", "cracks: pixels (max)",
           "popping: mean (max)", "popping: p99 (max)", "saturated frames (max)", "surplus: mean (cases' range)"},
          {},
          {false, false, false, true, true, true, true, true, true}};
  // One column per scheme counter (SchemeInfo::counters) of the schemes this run has: the sum of
  // its case key over the cases.
  std::vector<std::string> counterKeys;
  for (const Scheme* s : allSchemes()) {
    if (std::find(run.schemes.begin(), run.schemes.end(), s->info().name) == run.schemes.end()) continue;
    for (const SchemeCounter& c : s->info().counters) {
      t.header.push_back(s->info().name + ": " + c.label);
      t.numeric.push_back(true);
      counterKeys.push_back(c.caseKey);
    }
  }
  t.header.push_back("worst frames");
  t.numeric.push_back(false);
  for (auto& scheme : run.schemes)
    for (auto& scenario : run.scenarios) {
      std::vector<const ReportCase*> all, ok;
      int failed = 0, skipped = 0;
      for (auto& c : run.cases) {
        if (c.scheme != scheme || c.scenario != scenario) continue;
        all.push_back(&c);
        if (c.status == "ok") ok.push_back(&c);
        failed += c.status == "failed";
        skipped += c.status == "skipped";
      }
      if (all.empty()) continue;
      auto sat = maxOver(ok, "saturated_fraction", "").first;
      // Surplus (docs/results-format.md): the mean over a case's measured frames; range over the cases.
      std::optional<double> sLo, sHi;
      for (auto* c : ok)
        if (auto v = summaryStat(c->summary, "surplus", "mean")) {
          sLo = sLo ? std::min(*sLo, *v) : *v;
          sHi = sHi ? std::max(*sHi, *v) : *v;
        }
      std::string surplus = "–";
      if (sLo) {
        double mean = 0;
        int n = 0;
        for (auto* c : ok)
          if (auto v = summaryStat(c->summary, "surplus", "mean")) mean += *v, ++n;
        surplus = formatValue(mean / n) + (*sLo < *sHi ? " (" + formatValue(*sLo) + "–" + formatValue(*sHi) + ")" : "");
      }
      std::vector<Cell> row{
          schemeCell(run, scheme),
          textCell(scenario),
          textCell(std::to_string(ok.size()) + " / " + std::to_string(failed) + " / " + std::to_string(skipped)),
          textCell(formatValue(maxOver(ok, "cracks_analytic", "max").first)),
          textCell(formatValue(maxOver(ok, "cracks_pixels", "max").first)),
          textCell(formatValue(maxOver(ok, "pop_mean", "mean").first)),
          textCell(formatValue(maxOver(ok, "pop_p99", "max").first)),
          textCell(sat ? formatValue(100 * *sat) + " %" : "–"),
          textCell(surplus)};
      for (const std::string& key : counterKeys) {
        double frames = 0;
        bool any = false;
        for (auto* c : ok)
          if (auto u = plainNumber(c->summary, key.c_str())) frames += *u, any = true;
        row.push_back(textCell(any ? formatValue(frames) : "–"));
      }
      row.push_back(worstCell(run, ok, runHref));
      t.rows.push_back(std::move(row));
    }
  return t;
}

Table problemTable(const ReportRun& run) {
  Table t{{"case", "scheme", "parameters", "path", "status", "reason"}, {}, {}};
  for (auto& c : run.cases) {
    std::string reason = c.reason.empty() ? "(no reason recorded)" : c.reason;
    // A case that ran but left terrain out of a frame (or added some) failed on accuracy: its
    // error means cover drawn pixels only (metrics/coverage.h).
    auto cov = c.summary.find("coverage_failed_frames");
    if (c.status == "ok" && cov != c.summary.end() && cov->is_array() && !cov->empty()) {
      reason = "accuracy: terrain missing or extra beyond " + formatValue(kCoverageTolerance * 100) +
               "% of the truth's terrain pixels in measured frame(s)";
      for (auto& f : *cov) reason += " " + f.dump();
    } else if (c.status == "ok") {
      continue;
    }
    t.rows.push_back({codeCell(c.id), textCell(c.scheme), textCell(c.paramsLabel), textCell(c.scenario),
                      textCell(c.status), textCell(reason)});
  }
  return t;
}

}  // namespace lb
