#include "report/equal_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "report/memory_table.h"
#include "report/report_answer.h"
#include "schemes/registry.h"

namespace lb {

using nlohmann::json;

namespace {

const char* pathName(const std::string& scheme) {
  const Scheme* s = findScheme(scheme);
  if (!s) return "?";
  switch (s->info().path) {
    case DrawPath::Tessellation:
      return "tessellation";
    case DrawPath::InstancedGrid:
      return "instanced grid";
    case DrawPath::GpuIndirect:
      return s->info().tesc.empty() ? "GPU-indirect" : "GPU-indirect, tessellated";
    case DrawPath::Mesh:
      return "mesh shaders";
  }
  return "?";
}

// The share of the triangles drawn on measured frames that cover some ground: the clipper's count
// less the histogram's degenerate ones (zero ground area: morph collapses, clipmap strips).
std::optional<double> nonDegenerateShare(const ReportCase& c) {
  double all = 0, degenerate = 0;
  for (const json& f : c.frames) {
    auto clip = frameValue(f, "clip_invocations"), deg = frameValue(f, "hist_degenerate");
    if (clip && deg) all += *clip, degenerate += *deg;
  }
  if (all <= 0) return std::nullopt;
  return (all - degenerate) / all;
}

std::string percentText(const std::optional<double>& share) {
  if (!share) return formatValue(share);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f%%", 100.0 * *share);
  return buf;
}

std::string deviceName(const ReportRun& run) {
  auto it = run.context.find("device");
  return it != run.context.end() && it->is_string() ? it->get<std::string>() : "an unrecorded device";
}

struct Row {
  const ReportCase* c;
  double gpuMedian;
};

// The case's energy per frame (replay/energy_pass.h), when it was measured.
std::optional<EnergyFigure> energyOf(const ReportCase& c) {
  auto e = c.summary.find("energy_j_per_frame");
  if (e == c.summary.end() || !e->is_object()) return std::nullopt;
  for (const char* k : {"mean", "min", "max"})
    if (!(*e)[k].is_number()) return std::nullopt;
  EnergyFigure f{c.scheme, (*e)["mean"].get<double>(), (*e)["min"].get<double>(), (*e)["max"].get<double>(), 0};
  f.spread = (*e)["spread"].is_number() ? (*e)["spread"].get<double>() : 0;
  return f;
}

std::string jText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g J", v);
  return buf;
}

}  // namespace

std::string energyRanking(std::vector<EnergyFigure> f) {
  std::stable_sort(f.begin(), f.end(), [](const EnergyFigure& a, const EnergyFigure& b) { return a.mean < b.mean; });
  std::string out;
  for (size_t i = 0; i < f.size(); ++i) {
    if (i > 0) {
      // Ranked only where the highest round of every scheme so far lies below the lowest round of
      // every scheme from here on: a chain of "<" then never ranks two overlapping schemes.
      double below = -INFINITY, above = INFINITY;
      for (size_t k = 0; k < i; ++k) below = std::max(below, f[k].max);
      for (size_t k = i; k < f.size(); ++k) above = std::min(above, f[k].min);
      out += below < above ? " < " : " ≈ ";
    }
    out += f[i].label + " " + jText(f[i].mean) + " (spread " + percentText(f[i].spread) + ")";
  }
  return out;
}

// The mean popping at lags 1, 2 and 3 (replay/popping.h), "–" for a lag not measured.
static std::string poppingLags(const ReportCase& c) {
  std::string out;
  for (const char* k : {"pop_mean", "pop2_mean", "pop3_mean"})
    out += (out.empty() ? "" : " / ") + formatValue(summaryStat(c.summary, k, "mean"));
  return out;
}

EqualErrorSection equalErrorSection(const ReportRun& run) {
  EqualErrorSection out;
  std::vector<Row> rows;
  std::string metric;
  double target = 0;
  for (const ReportCase& c : run.cases) {
    if (c.status != "ok" || !c.matched.is_object() || !c.matched.contains("target")) continue;
    metric = c.matched.value("metric", "");
    target = c.matched.value("target", 0.0);
    rows.push_back({&c, summaryStat(c.summary, "gpu_ms", "median").value_or(INFINITY)});
  }
  if (rows.empty()) return out;
  out.present = true;
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.gpuMedian < b.gpuMedian; });
  out.title = "Cost at equal error: " + metric + " " + formatValue(target);
  out.intro =
      "Every scheme's main parameter was searched until its " + metric + " over the search's frames met " +
      formatValue(target) +
      " (config \"match\"); each row is the case run at the value found, cheapest GPU median first. LOD ms and "
      "draw ms split the frame where the draw path decides its LOD apart from drawing (instanced grid: the CPU "
      "selection is lod_cpu_ms, outside the GPU time; GPU-indirect: the compute passes); on the tessellation path "
      "the LOD decision runs inside the draw. FLIP mean is the perceived difference from the ray-cast truth "
      "(LDR-FLIP, 0 identical .. 1), averaged over the measured frames; popping is the mean RGB change (0..255) "
      "between the frame and the same view drawn with the LOD of 1, 2 and 3 frames before; lag frames is the "
      "longest run of frames whose mean error was more than 10 % off the error of the LOD settled at that camera "
      "(0 for a LOD of the camera alone). The non-degenerate share leaves out the zero-area triangles (morph "
      "collapses, clipmap strips) of the measured frames. GPU MiB is the device memory the case's renderer held "
      "(terrain, normal map, scheme tables, geometry, instances, LOD state, frame; capture buffers apart), \"of "
      "it LOD\" the scheme's own share (tables, geometry, instances, LOD state). Unreachable targets are marked: "
      "the search stopped at the parameter's bound.";
  const std::string device = deviceName(run);
  if (softwareRasterizer(device))
    out.caveat = "Caveat: " + device +
                 " is a software rasterizer. Tessellation is emulated on the CPU there, so these timings are no "
                 "verdict on the tessellator against the other draw paths; the errors and triangle counts hold on "
                 "any device.";
  out.table.header = {"scheme",
                      "draw path",
                      "matched parameter",
                      "search reached",
                      "error p95 px, run median",
                      "GPU ms median",
                      "GPU ms p95",
                      "energy J/frame",
                      "energy spread",
                      "GPU MiB",
                      "of it LOD MiB",
                      "LOD GPU ms",
                      "draw GPU ms",
                      "LOD CPU ms",
                      "triangles median",
                      "non-degenerate share",
                      "FLIP mean",
                      "popping lag 1 / 2 / 3",
                      "lag frames"};
  out.table.numeric = {false, false, false, false, true, true, true, true, true, true,
                       true,  true,  true,  true,  true, true, true, true, true};
  std::vector<EnergyFigure> energies;
  std::vector<std::pair<std::string, std::string>> unmeasured;  // scheme, why
  json data = json::array();
  for (const Row& r : rows) {
    const ReportCase& c = *r.c;
    const json& m = c.matched;
    const bool reachable = m.value("reachable", true);
    std::string param =
        m.value("param", "") + " = " + (m["value"].is_number() ? formatValue(m["value"].get<double>()) : "?");
    std::string reached = (m["achieved"].is_number() ? formatValue(m["achieved"].get<double>()) : "?") +
                          (reachable ? "" : " (unreachable)");
    auto gpu95 = summaryStat(c.summary, "gpu_ms", "p95");
    auto lod = summaryStat(c.summary, "lod_ms", "median"), draw = summaryStat(c.summary, "draw_ms", "median");
    const std::optional<EnergyFigure> energy = energyOf(c);
    if (energy)
      energies.push_back(*energy);
    else if (c.summary.contains("energy_reason"))
      unmeasured.push_back({c.scheme, c.summary["energy_reason"].is_string()
                                          ? c.summary["energy_reason"].get<std::string>()
                                          : std::string("not measured")});
    out.table.rows.push_back(
        {textCell(c.scheme), textCell(pathName(c.scheme)), textCell(param), textCell(reached),
         textCell(formatValue(summaryStat(c.summary, "err_p95_px", "median"))),
         textCell(formatValue(std::isfinite(r.gpuMedian) ? std::optional<double>(r.gpuMedian) : std::nullopt)),
         textCell(formatValue(gpu95)),
         textCell(formatValue(energy ? std::optional<double>(energy->mean) : std::nullopt)),
         textCell(energy ? percentText(energy->spread) : formatValue(std::nullopt)),
         textCell(mibText(memoryValue(c, "gpu_total_bytes"))), textCell(mibText(memoryValue(c, "gpu_lod_bytes"))),
         textCell(formatValue(lod)), textCell(formatValue(draw)),
         textCell(formatValue(summaryStat(c.summary, "lod_cpu_ms", "median"))),
         textCell(formatValue(summaryStat(c.summary, "triangles", "median"))),
         textCell(percentText(nonDegenerateShare(c))),
         textCell(formatValue(summaryStat(c.summary, "flip_mean", "mean"))), textCell(poppingLags(c)),
         textCell(formatValue(summaryStat(c.summary, "settle", "frames")))});
    if (!std::isfinite(r.gpuMedian)) continue;
    const std::string label = c.scheme + (reachable ? "" : " (unreachable)");
    if (lod && draw) {
      data.push_back({{"scheme", label}, {"part", "LOD passes"}, {"ms", *lod}, {"order", r.gpuMedian}});
      data.push_back({{"scheme", label}, {"part", "draw"}, {"ms", *draw}, {"order", r.gpuMedian}});
    } else {
      data.push_back(
          {{"scheme", label}, {"part", "frame (LOD inside the draw)"}, {"ms", r.gpuMedian}, {"order", r.gpuMedian}});
    }
    if (gpu95) data.push_back({{"scheme", label}, {"part", "p95"}, {"p95", *gpu95}, {"order", r.gpuMedian}});
  }
  // Energy at equal error: ranked only across the sensor's spread (the rounds of two schemes overlap:
  // not ranked). The H100's sensor is said to sample part of each window only.
  if (!energies.empty()) {
    out.energy =
        "Energy per frame at equal error (the board's energy counter over windows of whole counter ticks with the "
        "path looped; the mean of the rounds, spread = (max - min) / mean), lowest first: " +
        energyRanking(energies) +
        ". \"<\": every round of the schemes before it used less energy a frame than every round of those after "
        "it; \"≈\": their rounds overlap, within the sensor's spread, so they are not ranked on energy.";
    for (size_t i = 0; i < unmeasured.size(); ++i)
      out.energy += (i ? "; " : " Not measured: ") + unmeasured[i].first + " (" + unmeasured[i].second + ")";
    if (!unmeasured.empty()) out.energy += ".";
  } else if (!unmeasured.empty()) {
    out.energy = "Energy per frame: not measured (" + unmeasured.front().second + ").";
  }
  Chart& ch = out.chart;
  ch.id = "equal_error_gpu_ms";
  ch.section = "equal-error";
  ch.title = "GPU ms per frame at " + metric + " " + formatValue(target);
  ch.dataName = "equal_error";
  ch.data = data;
  const json y = {{"field", "scheme"},
                  {"type", "nominal"},
                  {"title", nullptr},
                  {"sort", {{"field", "order"}, {"op", "min"}, {"order", "ascending"}}}};
  ch.spec = {
      {"$schema", kVegaLiteSchema},
      {"title", ch.title},
      {"width", 560},
      {"data", {{"url", "data/equal_error.json"}}},
      {"layer",
       json::array(
           {{{"transform", json::array({{{"filter", "datum.part != 'p95'"}}})},
             {"mark", {{"type", "bar"}}},
             {"encoding",
              {{"y", y},
               {"x",
                {{"field", "ms"},
                 {"type", "quantitative"},
                 {"stack", "zero"},
                 {"title", "GPU ms/frame, median (bars) and p95 (tick)"}}},
               {"color",
                {{"field", "part"},
                 {"type", "nominal"},
                 {"title", "part of the frame"},
                 {"legend", {{"labelLimit", 320}}}}},
               {"tooltip",
                json::array({{{"field", "scheme"}}, {{"field", "part"}}, {{"field", "ms"}, {"format", ".3f"}}})}}}},
            {{"transform", json::array({{{"filter", "datum.part == 'p95'"}}})},
             {"mark", {{"type", "tick"}, {"color", "black"}, {"thickness", 2}}},
             {"encoding",
              {{"y", y},
               {"x", {{"field", "p95"}, {"type", "quantitative"}}},
               {"tooltip", json::array({{{"field", "scheme"}}, {{"field", "p95"}, {"format", ".3f"}}})}}}}})}};
  return out;
}

}  // namespace lb
