#include "sweep/runner.h"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "camera/camera_path.h"
#include "error.h"
#include "metrics/cracks.h"
#include "render/image_io.h"
#include "render/terrain_fit.h"
#include "sweep/case_images.h"
#include "schemes/registry.h"
#include "results/run_dir.h"
#include "sweep/gbench_json.h"
#include "sweep/progress.h"
#include "sweep/timing_passes.h"
#include "terrain/heightfield.h"
#include "terrain/terrain_cache.h"
#include "vk/context.h"
#include "vk/device_limits.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

static std::atomic<bool> gStop{false};

RenderMode parseRenderMode(const std::string& name) {
  if (name == "shaded") return RenderMode::Shaded;
  if (name == "heatmap") return RenderMode::Heatmap;
  if (name == "wireframe") return RenderMode::Wireframe;
  throw InputError("unknown render mode '" + name + "' (shaded, heatmap, wireframe)");
}

const char* renderModeName(RenderMode m) {
  return m == RenderMode::Heatmap ? "heatmap" : m == RenderMode::Wireframe ? "wireframe" : "shaded";
}

static double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Reference images are kept per terrain: keyed by its contents, so two terrains sharing a label
// (or a cache kept across runs) never lend each other images.
static std::string referenceKey(const Case& c) {
  return c.terrainDigest.empty() ? c.terrainLabel : c.terrainLabel + "#" + c.terrainDigest.substr(0, 16);
}

// Load-time stage costs per terrain label (run.json costs.terrains), from this invocation's cases:
// the latest case's figures, since every case loads its terrain and builds its renderer anew.
struct TerrainStageCosts {
  double loadS = -1, normalMapS = -1;
  std::map<std::string, double> preprocessS;  // by scheme
};
static std::map<std::string, TerrainStageCosts> gStageCosts;

static void recordStageCosts(const Case& c, double loadS, const Renderer::SetupCosts& setup) {
  TerrainStageCosts& t = gStageCosts[c.terrainLabel];
  t.loadS = loadS;
  t.normalMapS = setup.normalMapS;
  t.preprocessS[c.scheme] = setup.preprocessS;
}

static json stageCostsJson() {
  json out = json::object();
  for (const auto& [label, t] : gStageCosts)
    out[label] = {{"load_s", t.loadS}, {"normal_map_s", t.normalMapS}, {"preprocess_s", t.preprocessS}};
  return out;
}

CaseResult runCase(Context& ctx, const Case& c, const Config& config, const std::string& imageDir,
                   SweepProgress* progress, ReferenceCache& refs) {
  using Phase = SweepProgress::Phase;
  auto t0 = std::chrono::steady_clock::now();
  CaseResult result;
  const Scheme* scheme = findScheme(c.scheme);
  if (!scheme) throw InputError("unknown scheme '" + c.scheme + "'");
  const std::shared_ptr<const Heightfield> heldTerrain = sharedHeightfield(c.terrain);
  const Heightfield& terrain = *heldTerrain;
  const double loadS = secondsSince(t0);  // run.json costs.terrains: the terrain load alone
  result.terrainSource = terrain.source;  // the case file's terrain.source
  CameraPath path = loadCameraPath(c.path);
  RenderSettings settings{c.width, c.height, c.grid, config.testSlowdown};
  ParamValues params = c.params;
  if (config.match.on()) {
    MatchResult m = matchParameter(ctx, *scheme, params, terrain, path, config, c);
    if (!m.param.empty()) params[m.param] = m.value;
    result.matched = {{"metric", config.match.metric}, {"target", config.match.value}, {"param", m.param},
                      {"value", m.value}, {"achieved", m.achieved}, {"evaluations", m.evaluations},
                      {"reachable", m.reachable}};
  }
  Renderer renderer(ctx, terrain, settings);
  renderer.setScheme(*scheme, params);
  recordStageCosts(c, loadS, renderer.setupCosts());
  int frames = frameCount(path, config.fps);
  if (config.maxFrames > 0) frames = std::min(frames, config.maxFrames);
  auto pose = [&](int f) { return samplePose(path, config.fps, f, terrain); };

  if (progress) progress->phase(Phase::Timing);
  // Clock control: a fixed workload until its time is stable, so every case starts at a settled clock.
  std::unique_ptr<Calibrator> calibrator;
  CalibrationRun calibrationBefore;
  if (config.timing.calibrate) {
    calibrator = std::make_unique<Calibrator>(ctx, terrain, settings, config.timing, pose(0));
    calibrationBefore = calibrator->untilStable();
  }
  // Warm-up: the first pose, unrecorded, so caches, clocks and pipelines settle.
  for (int i = 0; i < config.warmupFrames; ++i) renderer.submitFrame(-1, pose(0), pose(0));
  renderer.finish();
  renderer.takeCompleted();

  int total = frames * config.repetitions;
  for (int rep = 0; rep < config.repetitions; ++rep)
    for (int f = 0; f < frames; ++f) {
      if (gStop) throw Interrupted();
      if (config.caseTimeoutS > 0 && secondsSince(t0) > config.caseTimeoutS)
        throw std::runtime_error("timeout: the case ran longer than " + std::to_string(config.caseTimeoutS) + " s");
      CameraPose p = pose(f);
      renderer.submitFrame(f, p, p);
      for (auto& r : renderer.takeCompleted()) result.frames.push_back(r);
      if (progress) progress->frame(rep * frames + f + 1, total);
    }
  renderer.finish();
  for (auto& r : renderer.takeCompleted()) result.frames.push_back(r);
  // Other timing modes: separate replays of the path; their tessellation counters must match.
  for (const std::string& m : config.timing.modes) {
    if (m == "shaded") continue;
    if (gStop) throw Interrupted();
    auto replay = replayInMode(renderer, timingRenderMode(m), frames, config.repetitions, config.warmupFrames, pose);
    std::string mismatch = compareTessellationCounters(result.frames, replay, m);
    if (!mismatch.empty()) throw std::runtime_error("timing modes disagree: " + mismatch);
    result.modeFrames[m] = std::move(replay);
  }
  if (calibrator) result.calibration = calibrationJson(calibrationBefore, calibrator->runOnce(), config.timing);
  result.targetAreaPx = scheme->targetAreaPx(renderer.params());

  // Measurement passes run after every timed frame, so they cannot perturb the timings.
  const MeasureSpec& ms = config.measure;
  std::map<int, FrameMetrics> kept;  // measured frames that images were asked for
  auto wantsImage = [&](int frame) {
    for (int f : config.images.frames)
      if ((f < 0 ? frames + f : f) == frame) return true;
    return false;
  };
  if (progress) progress->phase(Phase::Measure);
  if (ms.every > 0) {
    int count = (frames + ms.every - 1) / ms.every, done = 0;
    for (int f = 0; f < frames; f += ms.every) {
      if (gStop) throw Interrupted();
      FrameMetrics m = measureFrame(ctx, renderer, *scheme, renderer.params(), terrain, referenceKey(c), ms, refs, f,
                                    pose(std::max(0, f - 1)), pose(f));
      if (wantsImage(f)) kept[f] = m;
      m.shaded = {};
      m.reference = {};
      m.errorMap.clear();
      m.crackMask.clear();
      result.metrics.push_back(std::move(m));
      if (progress) progress->frame(++done, count);
    }
  }
  if (progress) progress->phase(Phase::Images);

  // Images for people are separate passes after the timed and measured frames, never inside them
  // (sweep/case_images.h): the configured frames and the worst measured ones.
  if (!config.images.modes.empty()) {
    json worst = result.metrics.empty() ? json() : caseSummary(result).value("worst_frames", json());
    CaseImageInputs in{ctx, c, config, *scheme, renderer, terrain, referenceKey(c), refs, pose, imageDir};
    result.images = writeCaseImages(in, imageFrames(config.images, frames, worst), kept);
  }
  result.seconds = secondsSince(t0);
  return result;
}

static std::string defaultRunDir(const Config& config) {
  std::string t = isoTimeUtc();  // 2026-11-21T19:36:00Z -> 20261121-193600
  std::string id;
  for (char ch : t)
    if (std::isdigit(static_cast<unsigned char>(ch))) id += ch;
  id.insert(8, "-");
  return "results/" + config.name + "/" + id;
}

void requestStop() { gStop = true; }

std::vector<Case> shardCases(const Config& config, int shardIndex, int shardCount) {
  std::vector<Case> all = expandCases(config), out;
  for (size_t i = 0; i < all.size(); ++i)
    if (int(i % size_t(shardCount)) == shardIndex) out.push_back(all[i]);
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
  if (count < 1 || index < 0 || index >= count)
    throw InputError("--shard '" + text + "': need 0 <= i < n");
}

// Temp files of an interrupted writer are never valid results.
static void removeStaleTemps(const std::string& dir) {
  for (auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename().string().find(".tmp") != std::string::npos) fs::remove(e.path());
}

RunTotals runSweep(const Config& config, const RunOptions& options) {
  gStop = false;
  RunTotals totals;
  totals.dir = options.outDir.empty() ? defaultRunDir(config) : options.outDir;
  std::string runJson = totals.dir + "/run.json";
  auto cases = shardCases(config, options.shardIndex, options.shardCount);
  // Every check on an existing directory comes before anything is written to it or a device opens.
  json previous;
  ResumePlan plan;
  if (hasRunJson(totals.dir)) {
    previous = readRunJson(totals.dir);
    plan = checkResume(totals.dir, previous, config.raw, options.shardIndex, options.shardCount, cases,
                       options.rerunChanged);
  }
  Context ctx;
  createContext(ctx, {config.device, options.validation});
  std::unique_ptr<Context, void (*)(Context*)> guard(&ctx, [](Context* c) { destroyContext(*c); });
  // Every terrain of this shard against the device's limits, before anything is written.
  const DeviceLimits limits = deviceLimits(ctx.physicalDevice);
  std::set<std::string> checked;
  for (const Case& c : cases)
    if (checked.insert(c.terrainLabel).second) checkTerrainFits(limits, c.terrain, c.terrainLabel);
  fs::create_directories(totals.dir + "/cases");
  fs::create_directories(totals.dir + "/images");
  removeStaleTemps(totals.dir);
  json context = runContext(ctx, config);
  json ids = json::array();
  for (auto& c : cases) ids.push_back(c.id);
  json run = {{"schema_version", kSchemaVersion}, {"context", context}, {"start_time", context["time"]},
              {"shard", {{"index", options.shardIndex}, {"count", options.shardCount}}}, {"case_ids", ids}};
  if (!previous.is_null()) {
    run["start_time"] = previous.value("start_time", context["time"].get<std::string>());
    run["resumed_at"] = previous.value("resumed_at", json::array());
    run["resumed_at"].push_back(context["time"]);
  }
  if (config.testSlowdown > 0) run["test_slowdown"] = config.testSlowdown;  // so no one mistakes it for data
  if (const char* off = std::getenv("LODBENCH_TEST_DISABLE"))  // features a test switched off (vk/context.cpp)
    run["test_disabled_features"] = off;
  writeFileAtomic(runJson, run.dump(2));

  std::vector<CaseWork> work = plannedWork(config, cases);
  for (size_t i = 0; i < cases.size(); ++i)
    if (plan.reuse.count(cases[i].id)) work[i] = CaseWork{cases[i].scheme, 0, 0, false};
  ReferenceCache refs(totals.dir + "/truth");  // ground-truth images persist for resume
  gStageCosts.clear();
  SweepProgress progress(options.progress, work, [&refs] {
    return SweepProgress::Truth{refs.rayCasts(), refs.rayCastSeconds()};
  });
  if (options.progress)
    std::fprintf(stderr, "lodbench: %zu cases on %s -> %s\n", cases.size(), ctx.props.deviceName, totals.dir.c_str());
  for (size_t i = 0; i < cases.size() && !totals.interrupted; ++i) {
    const Case& c = cases[i];
    std::string caseFile = totals.dir + "/cases/" + c.id + ".json";
    if (plan.reuse.count(c.id)) {  // finished with the same inputs (digest)
      totals.resumed++;
      totals.ok++;
      continue;
    }
    progress.startCase(i, c.id);
    CaseResult r;
    try {
      r = runCase(ctx, c, config, totals.dir + "/images", &progress, refs);
    } catch (const Interrupted&) {
      totals.interrupted = true;
      break;
    } catch (const FeatureMissing& e) {
      r.status = "skipped";
      r.reason = e.what();
    } catch (const std::exception& e) {
      r.status = "failed";
      r.reason = e.what();
      if (r.reason.find("VK_ERROR_DEVICE_LOST") != std::string::npos) {
        // A lost device is unusable: start a new one for the remaining cases.
        destroyContext(ctx);
        createContext(ctx, {config.device, options.validation});
      }
    }
    progress.endCase(r.status == "ok");
    if (options.progress) {
      json sum = caseSummary(r);
      if (r.status == "ok" && sum.contains("gpu_ms"))
        std::fprintf(stderr, "\r    ok: %zu frames, GPU median %.3f ms, %.0f triangles median, %.1fs\n", r.frames.size(),
                     sum["gpu_ms"]["median"].get<double>(), sum["triangles"]["median"].get<double>(), r.seconds);
      else
        std::fprintf(stderr, "\r    %s: %s\n", r.status.c_str(), r.reason.c_str());
    }
    (r.status == "ok" ? totals.ok : r.status == "skipped" ? totals.skipped : totals.failed)++;
    writeFileAtomic(caseFile, caseJson(c, r).dump(1));
    writeAggregates(totals.dir, context);
  }
  run["end_time"] = isoTimeUtc();
  // What each scheme's work cost in this invocation (the ETA's figures), to size configs by.
  json costs = json::object();
  double rayCast = progress.estimator().truthCost();
  run["ray_cast_s_per_image"] = rayCast >= 0 ? json(rayCast) : json(nullptr);
  for (auto& c : cases) {
    EtaEstimator::Own o = progress.estimator().own(c.scheme);
    auto val = [](double v) { return v >= 0 ? json(v) : json(nullptr); };
    if (o.timing >= 0)
      costs[c.scheme] = {{"timing_s_per_frame", val(o.timing)}, {"measured_s_per_frame", val(o.measured)},
                         {"case_overhead_s", val(o.overhead)}};
  }
  costs["terrains"] = stageCostsJson();  // no scheme is named "terrains"
  run["costs"] = costs;
  run["interrupted"] = totals.interrupted;
  run["totals"] = {{"ok", totals.ok}, {"failed", totals.failed}, {"skipped", totals.skipped}, {"cases", cases.size()}};
  run["validation_errors"] = ctx.validationErrors.load();
  writeFileAtomic(runJson, run.dump(2));
  writeAggregates(totals.dir, context);
  writeGoogleBenchmarkJson(totals.dir);  // summary in Google Benchmark's schema for its tools
  totals.validationErrors = ctx.validationErrors.load();
  return totals;
}

}  // namespace lb
