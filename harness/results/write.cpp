#include "results/write.h"

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "config/config.h"
#include "metrics/coverage.h"
#include "number_text.h"
#include "results/memory_json.h"
#include "schemes/plugins.h"
#include "schemes/registry.h"
#include "shaders/shared.h"
#include "stats.h"
#include "terrain/generators.h"
#include "version.h"
#include "vk/context.h"
#include "vk/device_identity.h"
#include "vk/energy_counter.h"

namespace lb {

using nlohmann::json;

void writeFileAtomic(const std::string& path, const std::string& contents) {
  std::string tmp = path + ".tmp" + std::to_string(::getpid());
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("cannot write " + tmp);
    f << contents;
    f.flush();
    if (!f) throw std::runtime_error("write failed: " + tmp);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp + " -> " + path);
}

std::string gitCommit() {
  // Set where the tree travels with a stale or no .git (a build carried to a GPU machine): it wins.
  if (const char* env = std::getenv("LODBENCH_GIT_COMMIT"); env && *env) return env;
  std::string cmd = std::string("git -C '") + LODBENCH_SOURCE_DIR + "' rev-parse HEAD 2>/dev/null";
  std::array<char, 128> buf{};
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    while (fgets(buf.data(), int(buf.size()), p)) out += buf.data();
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  if (out.empty()) return "unknown";
  std::string dirtyCmd =
      std::string("git -C '") + LODBENCH_SOURCE_DIR + "' status --porcelain --untracked-files=no 2>/dev/null";
  if (FILE* p = popen(dirtyCmd.c_str(), "r")) {
    if (fgets(buf.data(), int(buf.size()), p)) out += "-dirty";
    pclose(p);
  }
  return out;
}

std::string isoTimeUtc() {
  std::time_t t = std::time(nullptr);
  char s[32];
  std::strftime(s, sizeof s, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return s;
}

json runContext(const Context& ctx, const Config& config) {
  char host[256] = "unknown";
  gethostname(host, sizeof host - 1);
  const PowerLimit power = readPowerLimit(ctx.props.vendorID, ctx.deviceUuid);
  // The energy counter's tick, measured (up to two ticks of polling), and the board's clocks now
  // (idle: the run has not started; each case records the SM clock of its energy windows).
  const std::unique_ptr<EnergyCounter> energy = openEnergyCounter(ctx.props.vendorID, ctx.deviceUuid);
  double tickMs = -1;
  std::string energyReason = energy->reason();
  if (!config.timing.energy)
    energyReason = "\"energy\": false in the config";
  else if (energy->available() && (tickMs = measureTickMs(*energy, 3.0)) < 0)
    energyReason = "the energy counter (" + energy->name() + ") did not change twice in 3 s";
  const GpuClocks clocks = energy->clocks();
  auto mhz = [](int v) { return v >= 0 ? json(v) : json(nullptr); };
  json context = {
      {"tool", "lodbench"},
      {"tool_version", kToolVersion},
#ifdef NDEBUG
      {"build_type", "release"},
#else
      {"build_type", "debug"},
#endif
      {"git_commit", gitCommit()},
      {"device", ctx.props.deviceName},
      {"device_id", ctx.props.deviceID},
      {"vendor_id", ctx.props.vendorID},
      {"device_uuid", ctx.deviceUuid},
      {"driver_uuid", ctx.driverUuid},
      {"power_limit_w", power.watts >= 0 ? json(power.watts) : json(nullptr)},
      {"power_limit_enforced_w", power.enforcedWatts >= 0 ? json(power.enforcedWatts) : json(nullptr)},
      {"power_limit_reason", power.reason.empty() ? json(nullptr) : json(power.reason)},
      {"energy_counter", energy->available() ? json(energy->name()) : json(nullptr)},
      {"energy_tick_ms", tickMs > 0 ? json(tickMs) : json(nullptr)},
      {"energy_reason", energyReason.empty() ? json(nullptr) : json(energyReason)},
      {"sm_clock_mhz", mhz(clocks.smMhz)},
      {"sm_clock_max_mhz", mhz(clocks.smMaxMhz)},
      {"mem_clock_mhz", mhz(clocks.memMhz)},
      {"mem_clock_max_mhz", mhz(clocks.memMaxMhz)},
      {"clocks_reason", clocks.reason.empty() ? json(nullptr) : json(clocks.reason)},
      {"driver", ctx.driverName},
      {"driver_info", ctx.driverInfo},
      {"driver_version", driverVersionString(ctx.props)},
      {"api_version", apiVersionString(ctx.props.apiVersion)},
      {"timestamp_period_ns", ctx.props.limits.timestampPeriod},
      {"validation", ctx.validationEnabled},
      {"host", host},
      {"time", isoTimeUtc()},
      {"config_file", config.file},
      {"config", config.raw},
  };
  // Scheme libraries loaded for this run (config "plugins" or --plugin): report loads them again.
  for (const LoadedPlugin& p : loadedPlugins())
    context["plugins"].push_back({{"file", p.path},
                                  {"sha256", p.sha256},
                                  {"api_version", p.apiVersion},
                                  {"name", p.name},
                                  {"built_against", p.builtAgainst},
                                  {"schemes", p.schemes}});
  return context;
}

static json summaryOf(const std::vector<double>& v) {
  Summary s = summarize(v);
  return {{"median", s.median}, {"p5", s.p5},   {"p95", s.p95}, {"p99", s.p99},
          {"mean", s.mean},     {"min", s.min}, {"max", s.max}, {"stddev", s.stddev}};
}

// JSON has no NaN: unavailable metrics are null.
static json number(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

json caseSummary(const CaseResult& r) {
  if (r.frames.empty()) return json::object();
  std::vector<double> gpu, cpu, tris, patches, tes, frags, harness, lod, draw, lodCpu, instances;
  for (auto& f : r.frames) {
    if (f.lodMs >= 0) lod.push_back(f.lodMs);
    if (f.drawMs >= 0) draw.push_back(f.drawMs);
    if (f.lodCpuMs >= 0) lodCpu.push_back(f.lodCpuMs);
    if (f.lodMs >= 0) instances.push_back(double(f.instances));
    gpu.push_back(f.gpuMs);
    cpu.push_back(f.cpuMs);
    harness.push_back(f.harnessMs);
    tris.push_back(double(f.stats.clipInvocations));
    patches.push_back(double(f.stats.tcsPatches));
    tes.push_back(double(f.stats.tesInvocations));
    frags.push_back(double(f.stats.fsInvocations));
  }
  json g = summaryOf(gpu);
  double med = g["median"].get<double>();
  json out = {{"frames", r.frames.size()},
              {"gpu_ms", g},
              {"cpu_ms", summaryOf(cpu)},
              {"fps_median", med > 0 ? 1000.0 / med : 0.0},
              {"fps_mean", g["mean"].get<double>() > 0 ? 1000.0 / g["mean"].get<double>() : 0.0},
              {"triangles", summaryOf(tris)},
              {"patches", summaryOf(patches)},
              {"tes_invocations", summaryOf(tes)},
              {"fragment_invocations", summaryOf(frags)}};
  out["cpu_harness_ms"] = summaryOf(harness);
  // Draw paths that decide LOD apart from drawing (docs/results-format.md); null on the tessellation
  // path, whose LOD decision runs inside its draws (gpu_ms_frontend is the proxy there).
  out["lod_ms"] = lod.empty() ? json(nullptr) : summaryOf(lod);
  out["draw_ms"] = draw.empty() ? json(nullptr) : summaryOf(draw);
  out["lod_cpu_ms"] = lodCpu.empty() ? json(nullptr) : summaryOf(lodCpu);
  out["instances"] = instances.empty() ? json(nullptr) : summaryOf(instances);
  for (auto& [mode, frames] : r.modeFrames) {  // timing modes: gpu_ms_depth, gpu_ms_frontend
    std::vector<double> ms;
    for (auto& f : frames) ms.push_back(f.gpuMs);
    if (!ms.empty()) out["gpu_ms_" + mode] = summaryOf(ms);
  }
  if (!r.calibration.is_null()) out["calibration"] = r.calibration;
  if (r.lodState.is_object())
    for (const auto& [k, v] : r.lodState.items()) out[k] = v;
  if (r.energy.is_object())
    for (const auto& [k, v] : r.energy.items()) out[k] = v;
  if (r.settle.is_object()) out["settle"] = r.settle;
  out["memory"] = r.memory.is_object() ? r.memory : memoryUnknownJson("not recorded by the case's run");
  if (r.metrics.empty()) return out;
  // Per metric: statistics over the measured frames where it is available.
  std::map<std::string, std::vector<double>> series;
  std::map<std::string, std::pair<double, int>> worst;  // metric -> (value, frame)
  std::vector<uint64_t> histTotal(LB_HIST_BINS, 0);
  uint64_t offscreen = 0, backfacing = 0, degenerate = 0;
  int saturatedFrames = 0;
  // Schemes' own counters (SchemeInfo::counters): per frame key, the measured frames above 0.
  std::vector<const SchemeCounter*> counters;
  for (const Scheme* s : allSchemes())
    for (const SchemeCounter& counter : s->info().counters) counters.push_back(&counter);
  std::map<std::string, int> framesAbove;
  for (const FrameMetrics& m : r.metrics) {
    for (auto& [k, v] : m.values) {
      if (k.rfind("hist_", 0) == 0 || !std::isfinite(v)) continue;
      series[k].push_back(v);
      auto& w = worst[k];
      if (series[k].size() == 1 || v > w.first) w = {v, m.frame};
      if (k == "saturated_patches" && v > 0) ++saturatedFrames;
      if (v > 0)
        for (const SchemeCounter* counter : counters)
          if (k == counter->frameKey) ++framesAbove[k];
    }
    if (m.hasHistogram) {
      for (size_t i = 0; i < histTotal.size(); ++i) histTotal[i] += m.histogram.bins[i];
      offscreen += m.histogram.offscreen;
      backfacing += m.histogram.backfacing;
      degenerate += m.histogram.degenerate;
    }
  }
  for (auto& [k, v] : series) out[k] = summaryOf(v);
  out["measured_frames"] = r.metrics.size();
  bool anyHistogram = false;
  json unavailable = json::object();
  for (const FrameMetrics& m : r.metrics) {
    anyHistogram = anyHistogram || m.hasHistogram;
    for (auto& [pass, why] : m.unavailable) unavailable[pass] = why;
  }
  // Totals of a pass no frame could run are unknown, not zero.
  out["hist_total"] = anyHistogram ? json(histTotal) : json(nullptr);
  out["hist_offscreen_total"] = anyHistogram ? json(offscreen) : json(nullptr);
  out["hist_backfacing_total"] = anyHistogram ? json(backfacing) : json(nullptr);
  out["hist_degenerate_total"] = anyHistogram ? json(degenerate) : json(nullptr);
  if (!unavailable.empty()) out["unavailable"] = unavailable;
  // Unknown where no frame could count saturation (the instanced and GPU-indirect paths have no
  // tessellation levels: `unavailable` says so), not 0.
  out["saturated_fraction"] = series.count("saturated_patches")
                                  ? json(double(saturatedFrames) / double(series["saturated_patches"].size()))
                                  : json(nullptr);
  for (const SchemeCounter* counter : counters)
    if (series.count(counter->frameKey)) out[counter->caseKey] = framesAbove[counter->frameKey];
  // Coverage (metrics/coverage.h): the frames that miss or add terrain beyond the tolerance, one
  // that drew nothing where the truth has terrain among them, though its err_* are null.
  if (series.count("coverage_truth_px")) {
    json failed = json::array();
    for (const FrameMetrics& m : r.metrics)
      if (double t = metricValue(m, "coverage_truth_px");
          std::isfinite(t) &&
          coverageFailed(metricValue(m, "coverage_missing_px"), metricValue(m, "coverage_extra_px"), t))
        failed.push_back(m.frame);
    out["coverage_failed_frames"] = failed;
  }
  json wf = json::object();
  for (const char* k : {"cracks_pixels", "cracks_analytic", "pop_mean", "err_p95_px", "coverage_missing_px"})
    if (worst.count(k)) wf[k] = worst[k].second;
  out["worst_frames"] = wf;
  return out;
}

// "terrain.source": what a file terrain was read from; null for generated terrains and for a case
// that failed before reading it. Unknown fields are null, never left out.
static json sourceJson(const Case& c, const TerrainSource& s) {
  if (s.driver.empty()) return nullptr;
  auto orNull = [](bool known, json v) { return known ? v : json(nullptr); };
  const json& inputs = c.inputs.is_object() && c.inputs.contains("terrain") ? c.inputs["terrain"] : json();
  return {{"driver", s.driver},
          {"raster_size", {s.rasterWidth, s.rasterHeight}},
          {"band", s.band},
          {"data_type", s.dataType},
          {"crs", orNull(!s.crs.empty(), s.crs)},
          {"epsg", orNull(s.epsg != 0, s.epsg)},
          {"geotransform", orNull(!s.geoTransform.empty(), s.geoTransform)},
          {"nodata_count", s.nodataCount},
          {"window", orNull(!s.window.empty(), s.window)},
          {"overview", orNull(s.overview > 0, {{"level", s.overview}, {"method", s.overviewMethod}})},
          {"extent", s.extent},
          {"extent_source", s.extentSource},
          // The digest the case's identity already took of the file (config/case_identity.h).
          {"sha256", inputs.is_object() && inputs.contains("sha256") ? inputs["sha256"] : json(nullptr)}};
}

json measureCostsJson(const std::vector<FrameMetrics>& metrics) {
  if (metrics.empty()) return nullptr;
  std::map<std::string, double> sum;
  double total = 0;
  for (const FrameMetrics& m : metrics)
    for (const auto& [pass, s] : m.costs) sum[pass] += s, total += s;
  json passes = json::object();
  for (const auto& [pass, s] : sum) passes[pass] = 1e3 * s / double(metrics.size());
  return {{"frames", metrics.size()}, {"measured_frame", 1e3 * total / double(metrics.size())}, {"passes", passes}};
}

json caseJson(const Case& c, const CaseResult& r) {
  std::map<int, const FrameMetrics*> measured;
  for (auto& m : r.metrics) measured[m.frame] = &m;
  json frames = json::array();
  for (size_t fi = 0; fi < r.frames.size(); ++fi) {
    const FrameResult& f = r.frames[fi];
    json rec = {{"frame", f.frame},
                {"gpu_ms", f.gpuMs},
                {"cpu_ms", f.cpuMs},
                {"cpu_harness_ms", f.harnessMs},
                {"fps", f.gpuMs > 0 ? 1000.0 / f.gpuMs : 0.0},
                {"ia_vertices", f.stats.iaVertices},
                {"ia_primitives", f.stats.iaPrimitives},
                {"vs_invocations", f.stats.vsInvocations},
                {"patches", f.stats.tcsPatches},
                {"tes_invocations", f.stats.tesInvocations},
                {"clip_invocations", f.stats.clipInvocations},
                {"clip_primitives", f.stats.clipPrimitives},
                {"fragment_invocations", f.stats.fsInvocations},
                {"draws", f.draws}};
    // The instanced and GPU-indirect paths' split of the frame (FrameResult); absent on the
    // tessellation path. lod_cpu_ms is null where the LOD runs on the GPU.
    if (f.lodMs >= 0) {
      rec["instances"] = f.instances;
      rec["lod_ms"] = f.lodMs;
      rec["draw_ms"] = f.drawMs;
      rec["lod_cpu_ms"] = f.lodCpuMs >= 0 ? json(f.lodCpuMs) : json(nullptr);
    }
    for (auto& [mode, mf] : r.modeFrames)
      if (fi < mf.size()) rec["gpu_ms_" + mode] = mf[fi].gpuMs;
    auto it = measured.find(f.frame);
    if (it != measured.end()) {
      const FrameMetrics& m = *it->second;
      if (m.hasHistogram) {
        rec["hist"] = m.histogram.bins;
        rec["hist_offscreen"] = m.histogram.offscreen;
        rec["hist_backfacing"] = m.histogram.backfacing;
        rec["hist_degenerate"] = m.histogram.degenerate;
      } else if (m.unavailable.count("histogram")) {
        rec["hist"] = nullptr;
        rec["hist_offscreen"] = nullptr;
        rec["hist_backfacing"] = nullptr;
        rec["hist_degenerate"] = nullptr;
      }
      if (!m.unavailable.empty()) rec["unavailable"] = m.unavailable;
      for (auto& [k, v] : m.values)
        if (k.rfind("hist_", 0) != 0) rec[k] = number(v);
      measured.erase(it);  // repetitions replay the same frames: measurements attach to the first
    }
    frames.push_back(rec);
  }
  json params = json::object(), listed = json::object();
  for (auto& [k, v] : c.params) params[k] = v;
  for (auto& [k, v] : c.listedParams) listed[k] = v;
  if (r.matched.is_object() && !r.matched.value("param", "").empty())
    params[r.matched["param"]] = listed[r.matched["param"]] = r.matched["value"];
  if (r.matched.is_object() && r.matched.contains("tuned"))  // the tuned configuration's settings
    for (const auto& [k, v] : r.matched["tuned"]["chosen"].items())
      if (k != "grid") params[k] = listed[k] = v;
  json terrain = {{"type", c.terrain.type},
                  {"label", c.terrainLabel},
                  {"file", c.terrain.file},
                  // gdal without a config extent: the one derived from the file, once read
                  {"extent", c.terrain.extent > 0             ? json(c.terrain.extent)
                             : r.terrainSource.driver.empty() ? json(nullptr)
                                                              : json(r.terrainSource.extent)},
                  {"height_scale", c.terrain.heightScale},
                  // The grid of samples the case ran on, after a gdal window and overview; null
                  // when the case failed before the terrain was loaded.
                  {"samples", r.terrainWidth > 0 ? json({r.terrainWidth, r.terrainHeight}) : json(nullptr)},
                  {"source", sourceJson(c, r.terrainSource)}};
  if (c.terrain.type == "procedural" || isGeneratedTerrain(c.terrain.type)) {  // file terrains have neither
    terrain["size"] = c.terrain.size;
    terrain["seed"] = c.terrain.seed;
  }
  return {{"schema_version", kSchemaVersion},
          {"case_id", c.id},
          {"digest", c.digest},
          {"inputs", c.inputs},
          {"scheme", c.scheme},
          {"params", params},
          {"params_listed", listed},
          {"terrain", terrain},
          {"path", c.path},
          {"resolution", {c.width, c.height}},
          {"grid", r.grid > 0 ? r.grid : c.grid},
          {"image_reference", kImageReference},
          {"status", r.status},
          {"reason", r.reason},
          {"seconds", r.seconds},
          {"measure_costs_ms", measureCostsJson(r.metrics)},
          {"target_area_px", r.targetAreaPx > 0 ? json(r.targetAreaPx) : json(nullptr)},
          {"matched", r.matched},
          {"images", r.images},
          {"summary", caseSummary(r)},
          {"frames", frames}};
}

static const char* const kTimingColumns[] = {
    "frame",           "gpu_ms",           "cpu_ms",          "patches",
    "tes_invocations", "clip_invocations", "clip_primitives", "fragment_invocations"};

std::string framesCsvHeader(const std::vector<std::string>& params) {
  std::string h = "case_id";
  for (const char* c : kTimingColumns) h += std::string(",") + c;
  for (auto& c : metricColumns()) h += "," + c;
  h += ",scheme";
  for (auto& p : params) h += ",param_" + p;
  return h + "\n";
}

std::string framesCsvRows(const json& cj, const std::vector<std::string>& params) {
  std::string out;
  std::string id = cj.value("case_id", "");
  // The case's scheme and parameter values end every row, so the file filters without a join.
  std::string tail = "," + cj.value("scheme", "");
  const json noParams = json::object();
  const json& given = cj.contains("params") && cj["params"].is_object() ? cj["params"] : noParams;
  for (auto& p : params)
    tail += "," + (given.contains(p) && given[p].is_number() ? numberText(given[p].get<double>()) : std::string());
  for (const json& f : cj["frames"]) {
    out += id;
    for (const char* c : kTimingColumns) out += "," + (f.contains(c) ? f[c].dump() : std::string());
    for (const std::string& c : metricColumns()) {
      out += ",";
      if (c.rfind("hist_", 0) == 0 && std::isdigit(static_cast<unsigned char>(c[5]))) {
        if (f.contains("hist") && f["hist"].is_array()) out += f["hist"][size_t(std::stoi(c.substr(5)))].dump();
      } else if (f.contains(c) && !f[c].is_null()) {
        out += f[c].dump();
      }
    }
    out += tail + "\n";
  }
  return out;
}

}  // namespace lb
