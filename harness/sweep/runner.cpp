#include "sweep/runner.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "error.h"
#include "render/terrain_fit.h"
#include "replay/raycast_cache.h"
#include "results/gbench_json.h"
#include "results/run_dir.h"
#include "results/run_json.h"
#include "results/write.h"
#include "sweep/latest_link.h"
#include "sweep/progress.h"
#include "vk/context.h"
#include "vk/device_limits.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

static std::string defaultRunDir(const Config& config) {
  std::string t = isoTimeUtc();  // 2026-11-21T19:36:00Z -> 20261121-193600
  std::string id;
  for (char ch : t)
    if (std::isdigit(static_cast<unsigned char>(ch))) id += ch;
  id.insert(8, "-");
  return "results/" + config.name + "/" + id;
}

// Shards take contiguous blocks of whole workloads (a terrain, path, resolution and grid: the
// cases a verdict compares), so every scheme of a workload is timed on the same GPU, a shard
// computes each ground-truth image once and loads each large terrain once per round. With fewer
// workloads than shards, contiguous blocks of cases instead.
std::vector<Case> shardCases(const Config& config, int shardIndex, int shardCount) {
  std::vector<Case> all = expandCases(config), out;
  std::vector<size_t> unitOf(all.size());  // each case's workload index
  size_t units = 0;
  for (size_t i = 0; i < all.size(); ++i) {
    const Case& c = all[i];
    const bool same = i > 0 && all[i - 1].terrainLabel == c.terrainLabel && all[i - 1].path == c.path &&
                      all[i - 1].width == c.width && all[i - 1].height == c.height && all[i - 1].grid == c.grid;
    if (i > 0 && !same) ++units;
    unitOf[i] = units;
  }
  units = all.empty() ? 0 : units + 1;
  const bool byWorkload = units >= size_t(shardCount);
  const size_t n = size_t(shardCount), s = size_t(shardIndex), total = byWorkload ? units : all.size();
  const size_t begin = (s * total + n - 1) / n, end = ((s + 1) * total + n - 1) / n;
  for (size_t i = 0; i < all.size(); ++i) {
    const size_t u = byWorkload ? unitOf[i] : i;
    if (u >= begin && u < end) out.push_back(all[i]);
  }
  return out;
}

void parseShard(const std::string& text, int& index, int& count) {
  auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    index = std::stoi(text.substr(0, slash));
    count = std::stoi(text.substr(slash + 1));
  } catch (const std::exception&) {
    throw InputError("--shard '" + text + "': expected i/n, e.g. 0/4");
  }
  if (count < 1 || index < 0 || index >= count) throw InputError("--shard '" + text + "': need 0 <= i < n");
}

// Temp files of an interrupted writer are never valid results.
static void removeStaleTemps(const std::string& dir) {
  for (auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string().find(".tmp") != std::string::npos) fs::remove(e.path());
}

RunTotals runSweep(const Config& config, const RunOptions& options) {
  clearStop();
  RunTotals totals;
  totals.dir = options.outDir.empty() ? defaultRunDir(config) : options.outDir;
  std::string runJson = totals.dir + "/run.json";
  auto cases = shardCases(config, options.shardIndex, options.shardCount);
  // Every check on an existing directory comes before anything is written to it or a device opens.
  json previous;
  ResumePlan plan;
  if (hasRunJson(totals.dir)) {
    previous = readRunJson(totals.dir);
    plan = checkResume(totals.dir, previous, options.shardIndex, options.shardCount, cases, options.rerunChanged);
  }
  Context ctx;
  createContext(ctx, {config.device, options.validation, config.deviceWhere});
  std::unique_ptr<Context, void (*)(Context*)> guard(&ctx, [](Context* c) { destroyContext(*c); });
  // Every terrain of this shard against the device's limits, before anything is written.
  const DeviceLimits limits = deviceLimits(ctx.physicalDevice);
  std::set<std::string> checked;
  for (const Case& c : cases)
    if (checked.insert(c.terrainLabel).second) checkTerrainFits(limits, c.terrain, c.terrainLabel);
  json context = runContext(ctx, config);
  if (!previous.is_null()) checkSameDevice(totals.dir, previous, context);
  fs::create_directories(totals.dir + "/cases");
  fs::create_directories(totals.dir + "/images");
  if (config.match.on()) fs::create_directories(totals.dir + "/searches");
  removeStaleTemps(totals.dir);
  if (options.outDir.empty()) pointLatestAt(totals.dir);
  std::vector<std::string> ids;
  for (auto& c : cases) ids.push_back(c.id);
  json run = startedRunJson(context, options.shardIndex, options.shardCount, ids, previous);
  run["stale_cases"] = plan.stale;  // on disk, out of the run: readCaseFiles leaves them out
  if (previous.contains("costs")) run["costs"] = previous["costs"];         // until this invocation's end
  if (config.testSlowdown > 0) run["test_slowdown"] = config.testSlowdown;  // so no one mistakes it for data
  if (const char* off = std::getenv("LODBENCH_TEST_DISABLE"))  // features a test switched off (vk/context.cpp)
    run["test_disabled_features"] = off;
  writeFileAtomic(runJson, run.dump(2));

  std::vector<CaseWork> work = plannedWork(config, cases);
  for (size_t i = 0; i < cases.size(); ++i)
    if (plan.reuse.count(cases[i].id)) work[i] = CaseWork{cases[i].scheme, 0, 0, false};
  ReferenceCache refs(totals.dir + "/truth");  // ground-truth images persist for resume
  clearStageCosts();
  SweepProgress progress(options.progress, work, [&refs] {
    return SweepProgress::Truth{refs.rayCasts(), refs.rayCastSeconds()};
  });
  if (options.progress)
    std::fprintf(stderr, "lodbench: %zu cases on %s -> %s\n", cases.size(), ctx.props.deviceName, totals.dir.c_str());
  std::vector<FrameMetrics> costFrames;  // this invocation's measured frames, their pass costs only
  // One case under `cfg`: its result, a failure or skip recorded; false when interrupted.
  auto attempt = [&](const Case& c, const Config& cfg, SweepProgress* p, CaseResult& r) {
    try {
      // A matched case's search outlives an interrupted invocation (replay/case_search.h).
      const std::string search = cfg.match.on() ? totals.dir + "/searches/" + c.id + ".json" : "";
      r = runCase(ctx, c, cfg, totals.dir + "/images", p, refs, search);
    } catch (const Interrupted&) {
      totals.interrupted = true;
      return false;
    } catch (const FeatureMissing& e) {
      r.status = "skipped";
      r.reason = e.what();
    } catch (const std::exception& e) {
      r.status = "failed";
      r.reason = e.what();
      if (r.reason.find("VK_ERROR_DEVICE_LOST") != std::string::npos) {
        // A lost device is unusable: start a new one for the remaining cases.
        destroyContext(ctx);
        createContext(ctx, {config.device, options.validation, config.deviceWhere});
      }
    }
    return true;
  };
  // Interleaved repetitions (Config::interleave): the first round runs every case with one
  // repetition as usual (search, measurement, images); each later round times every case once
  // more with the first round's parameters and grid (no search, measurement or images), its frames
  // appended as the next repetition. Cases are written after the last round.
  const bool interleaved = config.interleave && config.repetitions > 1;
  Config firstRound = config;
  if (interleaved) firstRound.repetitions = 1;
  std::vector<std::pair<size_t, CaseResult>> held;  // interleaved: cases waiting for their rounds
  auto finish = [&](const Case& c, CaseResult& r) {
    for (const FrameMetrics& m : r.metrics) {
      FrameMetrics cost;
      cost.costs = m.costs;
      costFrames.push_back(std::move(cost));
    }
    (r.status == "ok" ? totals.ok : r.status == "skipped" ? totals.skipped : totals.failed)++;
    writeFileAtomic(totals.dir + "/cases/" + c.id + ".json", caseJson(c, r).dump(1));
    writeAggregates(totals.dir, context);
  };
  for (size_t i = 0; i < cases.size() && !totals.interrupted; ++i) {
    const Case& c = cases[i];
    if (plan.reuse.count(c.id)) {  // finished with the same inputs (digest)
      totals.resumed++;
      totals.ok++;
      continue;
    }
    progress.startCase(i, c.id);
    CaseResult r;
    if (!attempt(c, firstRound, &progress, r)) break;
    progress.endCase(r.status == "ok");
    if (options.progress) {
      json sum = caseSummary(r);
      if (r.status == "ok" && sum.contains("gpu_ms"))
        std::fprintf(stderr, "\r    ok: %zu frames, GPU median %.3f ms, %.0f triangles median, %.1fs\n",
                     r.frames.size(), sum["gpu_ms"]["median"].get<double>(), sum["triangles"]["median"].get<double>(),
                     r.seconds);
      else
        std::fprintf(stderr, "\r    %s: %s\n", r.status.c_str(), r.reason.c_str());
    }
    if (interleaved)
      held.emplace_back(i, std::move(r));
    else
      finish(c, r);
  }
  for (int round = 2; interleaved && round <= config.repetitions && !totals.interrupted; ++round) {
    Config later = config;
    later.repetitions = 1;
    later.match = {};
    later.measure.every = 0;
    later.images.modes.clear();
    later.timing.energy = false;
    for (auto& [i, r] : held) {
      if (r.status != "ok" || totals.interrupted) continue;
      Case c = cases[i];
      c.params = r.params;
      if (r.grid > 0) c.grid = r.grid;
      c.tune.clear();
      if (options.progress) std::fprintf(stderr, "  round %d/%d: %s\n", round, config.repetitions, cases[i].id.c_str());
      CaseResult more;
      if (!attempt(c, later, nullptr, more)) break;
      if (more.status != "ok") {
        r.status = more.status;
        r.reason = "round " + std::to_string(round) + ": " + more.reason;
        continue;
      }
      r.frames.insert(r.frames.end(), more.frames.begin(), more.frames.end());
      for (auto& [mode, frames] : more.modeFrames)
        r.modeFrames[mode].insert(r.modeFrames[mode].end(), frames.begin(), frames.end());
      r.seconds += more.seconds;
    }
  }
  // An interrupted interleaved sweep keeps none of its unfinished cases: a resume runs them anew.
  if (!totals.interrupted)
    for (auto& [i, r] : held) finish(cases[i], r);
  // What each scheme's work cost in this invocation (the ETA's figures), to size configs by.
  RunEnd end;
  end.costs = json::object();
  end.rayCastSPerImage = progress.estimator().truthCost();
  for (auto& c : cases) {
    EtaEstimator::Own o = progress.estimator().own(c.scheme);
    auto val = [](double v) { return v >= 0 ? json(v) : json(nullptr); };
    if (o.timing >= 0)
      end.costs[c.scheme] = {{"timing_s_per_frame", val(o.timing)},
                             {"measured_s_per_frame", val(o.measured)},
                             {"case_overhead_s", val(o.overhead)}};
  }
  // A grown sweep measures only its new schemes: the others keep their earlier figures.
  if (previous.contains("costs") && previous["costs"].is_object())
    for (auto& [scheme, cost] : previous["costs"].items())
      if (scheme != "terrains" && !end.costs.contains(scheme)) end.costs[scheme] = cost;
  end.costs["terrains"] = stageCostsJson();  // no scheme is named "terrains"
  end.measureCosts = measureCostsJson(costFrames);
  end.interrupted = totals.interrupted;
  end.ok = totals.ok;
  end.failed = totals.failed;
  end.skipped = totals.skipped;
  end.cases = cases.size();
  end.validationErrors = ctx.validationErrors.load();
  endRunJson(run, end);
  writeFileAtomic(runJson, run.dump(2));
  writeAggregates(totals.dir, context);
  writeGoogleBenchmarkJson(totals.dir);  // summary in Google Benchmark's schema for its tools
  totals.validationErrors = ctx.validationErrors.load();
  return totals;
}

}  // namespace lb
