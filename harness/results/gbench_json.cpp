#include "results/gbench_json.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <tuple>

#include "error.h"
#include "results/run_dir.h"
#include "results/write.h"
#include "stats.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Times are written in microseconds: compare.py prints them as whole numbers of the file's unit, so
// a 0.78 ms frame in "ms" read "1".
constexpr double kUsPerMs = 1000.0;

std::string readLine(const std::string& file) {
  std::ifstream in(file);
  std::string s;
  std::getline(in, s);
  return s;
}

// "0-1,4" -> 3
int countCpuList(const std::string& list) {
  int n = 0;
  std::stringstream ss(list);
  for (std::string part; std::getline(ss, part, ',');) {
    auto dash = part.find('-');
    n += dash == std::string::npos ? 1 : std::atoi(part.c_str() + dash + 1) - std::atoi(part.c_str()) + 1;
  }
  return n;
}

// Google Benchmark's cache entries, from sysfs (empty where it is absent).
json cpuCaches() {
  json caches = json::array();
  for (int i = 0;; ++i) {
    std::string d = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(i);
    if (!fs::exists(d)) break;
    std::string size = readLine(d + "/size");  // "32K", "1024K", "8M"
    long bytes = std::atol(size.c_str());
    if (!size.empty() && size.back() == 'K') bytes *= 1024;
    if (!size.empty() && size.back() == 'M') bytes *= 1024 * 1024;
    caches.push_back({{"type", readLine(d + "/type")},
                      {"level", std::atoi(readLine(d + "/level").c_str())},
                      {"size", bytes},
                      {"num_sharing", countCpuList(readLine(d + "/shared_cpu_list"))}});
  }
  return caches;
}

double cpuMhz() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("cpu MHz", 0) == 0) return std::atof(line.c_str() + line.find(':') + 1);
  return 0;
}

std::string executablePath() {
  std::error_code ec;
  fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "lodbench" : p.string();
}

std::string ctxString(const json& ctx, const char* key, const std::string& fallback = "") {
  return ctx.contains(key) && ctx[key].is_string() ? ctx[key].get<std::string>() : fallback;
}

// merged: a run merge wrote (run.json merged_from), whose cases ran on other machines: the facts of
// the machine writing the file (executable, CPUs, caches, load) would describe the merge, and
// change from one merge of the same folders to the next, so they are left out.
json contextBlock(const std::string& runDir, const json& ctx, bool merged) {
  std::string time = ctxString(ctx, "time", isoTimeUtc());  // 2026-11-21T20:05:38Z
  if (!time.empty() && time.back() == 'Z') time.replace(time.size() - 1, 1, "+00:00");
  json c = {{"date", time},
            {"host_name", ctxString(ctx, "host", "unknown")},
            {"library_build_type", ctxString(ctx, "build_type", "unknown")},
            {"json_schema_version", 1},
            {"lodbench_schema_version", kSchemaVersion},
            {"run_dir", runDir}};
  if (!merged) {
    double load[3] = {0, 0, 0};
    int nLoad = getloadavg(load, 3);
    json loadAvg = json::array();
    for (int i = 0; i < nLoad; ++i) loadAvg.push_back(load[i]);
    std::string governor = readLine("/sys/devices/system/cpu/cpu0/cpufreq/scaling_governor");
    c.update({{"executable", executablePath()},
              {"num_cpus", std::max(1u, std::thread::hardware_concurrency())},
              {"mhz_per_cpu", int(cpuMhz())},
              {"cpu_scaling_enabled", !governor.empty() && governor != "performance"},
              {"caches", cpuCaches()},
              {"load_avg", loadAvg}});
  }
  for (const char* key : {"tool_version", "git_commit", "device", "device_uuid", "driver", "driver_info", "api_version",
                          "timestamp_period_ns", "power_limit_w"})
    if (ctx.contains(key)) c[key] = ctx[key];
  return c;
}

double medianOf(const json& frames, size_t begin, size_t end, const char* key) {
  std::vector<double> v;
  for (size_t i = begin; i < end; ++i)
    if (frames[i].contains(key) && frames[i][key].is_number()) v.push_back(frames[i][key].get<double>());
  return percentile(v, 50);
}

// Counters of one repetition (its frames) plus the case's measurement means (from the summary).
void addCounters(json& entry, const json& frames, size_t begin, size_t end, const json& summary) {
  static const std::pair<const char*, const char*> kFrameCounters[] = {
      {"triangles", "clip_invocations"},
      {"patches", "patches"},
      {"tes_invocations", "tes_invocations"},
      {"fragment_invocations", "fragment_invocations"}};
  for (auto& [name, key] : kFrameCounters) entry[name] = medianOf(frames, begin, end, key);
  double gpuUs = entry["real_time"].get<double>();
  entry["fps"] = gpuUs > 0 ? 1e6 / gpuUs : 0.0;
  for (auto& [key, v] : summary.items()) {
    if (entry.contains(key) || key == "gpu_ms" || key == "cpu_ms" || key == "frames") continue;
    if (v.is_object() && v.contains("mean") && v["mean"].is_number())
      entry[key] = v["mean"];
    else if (v.is_number() && key.rfind("fps", 0) != 0)
      entry[key] = v;
  }
}

}  // namespace

json googleBenchmarkJson(const std::string& runDir) {
  if (!fs::is_directory(runDir)) throw InputError(runDir + ": no such run directory");
  json run = readRunJson(runDir);
  json ctx = run.value("context", json::object());
  int reps = 1;
  if (ctx.contains("config") && ctx["config"].is_object()) reps = std::max(1, ctx["config"].value("repetitions", 1));

  json benchmarks = json::array();
  int family = 0;
  for (auto& cf : readCaseFiles(runDir)) {
    const json& cj = cf.doc;
    std::string id = cf.id();
    json frames = cj.value("frames", json::array());
    json summary = cj.value("summary", json::object());
    json base = {{"name", id},       {"family_index", family++}, {"per_family_instance_index", 0},
                 {"run_name", id},   {"run_type", "iteration"},  {"threads", 1},
                 {"time_unit", "us"}};
    if (cj.value("status", "ok") != "ok" || frames.empty()) {
      json e = base;  // recorded with its reason, as Google Benchmark records a skipped run
      e.update({{"repetitions", 1},
                {"repetition_index", 0},
                {"iterations", 0},
                {"real_time", 0.0},
                {"cpu_time", 0.0},
                {"error_occurred", true},
                {"error_message", cj.value("status", "failed") + ": " + cj.value("reason", "no frames")}});
      benchmarks.push_back(e);
      continue;
    }
    int n = frames.size() % size_t(reps) == 0 ? reps : 1;  // frames are stored repetition after repetition
    size_t per = frames.size() / size_t(n);
    std::vector<double> real, cpu;
    for (int r = 0; r < n; ++r) {
      size_t b = size_t(r) * per, e = b + per;
      json entry = base;
      entry.update({{"repetitions", n},
                    {"repetition_index", r},
                    {"iterations", per},
                    {"real_time", kUsPerMs * medianOf(frames, b, e, "gpu_ms")},
                    {"cpu_time", kUsPerMs * medianOf(frames, b, e, "cpu_ms")}});
      addCounters(entry, frames, b, e, summary);
      real.push_back(entry["real_time"]);
      cpu.push_back(entry["cpu_time"]);
      benchmarks.push_back(entry);
    }
    if (n < 2) continue;
    Summary sr = summarize(real), sc = summarize(cpu);
    // Google Benchmark's stddev aggregate is the sample (n - 1) standard deviation.
    double k = std::sqrt(double(n) / double(n - 1));
    for (auto [name, rv, cv] : {std::tuple{"mean", sr.mean, sc.mean}, std::tuple{"median", sr.median, sc.median},
                                std::tuple{"stddev", sr.stddev * k, sc.stddev * k}}) {
      json a = base;
      a.update({{"name", id + "_" + name},
                {"run_type", "aggregate"},
                {"repetitions", n},
                {"aggregate_name", name},
                {"aggregate_unit", "time"},
                {"iterations", n},
                {"real_time", rv},
                {"cpu_time", cv}});
      benchmarks.push_back(a);
    }
  }
  return {{"context", contextBlock(runDir, ctx, run.contains("merged_from"))}, {"benchmarks", benchmarks}};
}

std::string writeGoogleBenchmarkJson(const std::string& runDir) {
  std::string path = runDir + "/gbench.json";
  writeFileAtomic(path, googleBenchmarkJson(runDir).dump(2) + "\n");
  return path;
}

}  // namespace lb
