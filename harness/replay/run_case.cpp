#include "replay/run_case.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

#include "camera/camera_path.h"
#include "error.h"
#include "render/lod_state.h"
#include "render/renderer.h"
#include "replay/case_images.h"
#include "replay/case_search.h"
#include "replay/energy_pass.h"
#include "replay/lod_replay.h"
#include "replay/matched.h"
#include "replay/measure.h"
#include "replay/settle.h"
#include "replay/timing_passes.h"
#include "results/memory_json.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "terrain/terrain_cache.h"
#include "vk/context.h"
#include "vk/energy_counter.h"

namespace lb {

using nlohmann::json;

static std::atomic<bool> gStop{false};

void requestStop() {
  gStop = true;
}
void clearStop() {
  gStop = false;
}

RenderMode parseRenderMode(const std::string& name) {
  if (name == "shaded") return RenderMode::Shaded;
  if (name == "heatmap") return RenderMode::Heatmap;
  if (name == "wireframe") return RenderMode::Wireframe;
  throw InputError("unknown render mode '" + name + "' (shaded, heatmap, wireframe)");
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
// each stage's largest figure, which is the case that did the work: a kept terrain's later cases
// take its heights and normal map from the cache, and a cached scheme table is a lookup.
struct TerrainStageCosts {
  double loadS = -1, pagesS = -1, normalMapS = -1;
  std::map<std::string, double> preprocessS;  // by scheme
};
static std::map<std::string, TerrainStageCosts> gStageCosts;

void clearStageCosts() {
  gStageCosts.clear();
}

void recordStageCosts(const std::string& terrain, const std::string& scheme, double loadS, double pagesS,
                      double normalMapS, double preprocessS) {
  TerrainStageCosts& t = gStageCosts[terrain];
  t.loadS = std::max(t.loadS, loadS);
  t.pagesS = std::max(t.pagesS, pagesS);
  t.normalMapS = std::max(t.normalMapS, normalMapS);
  auto [at, fresh] = t.preprocessS.emplace(scheme, preprocessS);
  if (!fresh) at->second = std::max(at->second, preprocessS);
}

json stageCostsJson() {
  json out = json::object();
  for (const auto& [label, t] : gStageCosts)
    out[label] = {
        {"load_s", t.loadS}, {"pages_s", t.pagesS}, {"normal_map_s", t.normalMapS}, {"preprocess_s", t.preprocessS}};
  return out;
}

CaseResult runCase(Context& ctx, const Case& c, const Config& config, const std::string& imageDir,
                   CaseProgress* progress, ReferenceCache& refs, const std::string& searchCheckpoint) {
  using Phase = CaseProgress::Phase;
  auto t0 = std::chrono::steady_clock::now();
  // The case's own peak host memory: the high-water mark starts at the resident set now.
  const bool hostPeakReset = resetHostPeak();
  CaseResult result;
  const Scheme* scheme = findScheme(c.scheme);
  if (!scheme) throw InputError("unknown scheme '" + c.scheme + "'");
  const std::shared_ptr<const Heightfield> heldTerrain = sharedHeightfield(c.terrain);
  const Heightfield& terrain = *heldTerrain;
  const double loadS = secondsSince(t0);  // run.json costs.terrains: the terrain load alone
  result.terrainSource = terrain.source;  // the case file's terrain.source
  result.terrainWidth = terrain.width;    // and terrain.samples
  result.terrainHeight = terrain.height;
  CameraPath path = loadCameraPath(c.path);
  RenderSettings settings{c.width, c.height, c.grid, config.testSlowdown};
  ParamValues params = c.params;
  if (config.match.on()) {
    CaseSearch search = searchCase(ctx, *scheme, params, terrain, path, config, c, searchCheckpoint);
    params = search.params;
    if (search.grid > 0) settings.grid = result.grid = search.grid;
    result.matched = std::move(search.matched);
  }
  result.params = params;
  Renderer renderer(ctx, terrain, settings);
  renderer.setScheme(*scheme, params);
  const Renderer::SetupCosts& setup = renderer.setupCosts();
  recordStageCosts(c.terrainLabel, c.scheme, loadS, setup.pagesS, setup.normalMapS, setup.preprocessS);
  int frames = frameCount(path, config.fps);
  if (config.maxFrames > 0) frames = std::min(frames, config.maxFrames);
  auto pose = [&](int f) { return samplePose(path, config.fps, f, terrain); };
  // A stateful scheme starts every timed pass from the same converged state (replay/lod_replay.h).
  const bool stateful = renderer.statefulLod();
  if (stateful) {
    ConvergeResult converged = convergeLod(renderer, pose(0));
    result.lodState = lodStateJson(converged, renderer.lodState().gpuLod().facts);
  }

  if (progress) progress->phase(Phase::Timing);
  // Clock control: a fixed workload until its time is stable, so every case starts at a settled clock.
  std::unique_ptr<Calibrator> calibrator;
  CalibrationRun calibrationBefore;
  const bool calibrate = calibrationWanted(config.timing, ctx);
  if (calibrate) {
    calibrator = std::make_unique<Calibrator>(ctx, terrain, settings, config.timing, pose(0));
    calibrationBefore = calibrator->untilStable();
  }
  // Warm-up: the first pose, unrecorded, so caches, clocks and pipelines settle.
  for (int i = 0; i < config.warmupFrames; ++i) renderer.submitFrame(-1, pose(0), pose(0));
  renderer.finish();
  renderer.takeCompleted();
  if (stateful) renderer.lodState().snapshot();

  int total = frames * config.repetitions;
  for (int rep = 0; rep < config.repetitions; ++rep)
    for (int f = 0; f < frames; ++f) {
      if (stateful && f == 0) renderer.lodState().restore();
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
  result.calibration = calibrator ? calibrationJson(calibrationBefore, calibrator->runOnce(), config.timing)
                                  : uncalibratedJson(config.timing, ctx);
  // Energy per frame where the board has a counter (NVML): windows of whole ticks with the path
  // looped, after the calibration's after-run so they do not move its drift.
  {
    const std::unique_ptr<EnergyCounter> counter = openEnergyCounter(ctx.props.vendorID, ctx.deviceUuid);
    result.energy = energyJson(energyPass(renderer, *counter, config.timing, frames, pose, [] {
      if (gStop) throw Interrupted();
    }));
  }
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
  std::vector<uint32_t> timedLod;  // stateful: the first repetition's instances, frame by frame
  const int measuredCount = ms.every > 0 ? (frames + ms.every - 1) / ms.every : 0;
  int done = 0;
  // A measured frame's numbers stay (its pixels too where an image of it was asked for).
  auto keep = [&](FrameMetrics m) {
    if (wantsImage(m.frame)) kept[m.frame] = m;
    m.shaded = {};
    m.reference = {};
    m.errorMap.clear();
    m.crackMask.clear();
    m.flipMap.clear();
    result.metrics.push_back(std::move(m));
    if (progress) progress->frame(++done, measuredCount);
  };
  if (stateful) {
    timedLod = timedInstances(result.frames, frames);
    LodReplay replay(renderer, pose, timedLod);
    auto isMeasured = [&](int f) { return ms.every > 0 && f < frames && f % ms.every == 0; };
    std::map<int, OlderLod> older;  // popping at lags 2 and 3: earlier states drawn from a measured frame's view
    for (int f = 0; f < frames; ++f) {
      if (gStop) throw Interrupted();
      const bool measured = isMeasured(f);
      // Before frame f's update the state is frame f - 1's: lag k of frame f - 1 + k.
      for (int k = 2; ms.on("popping") && f >= 1 && k <= kPopLags; ++k)
        if (int t = f - 1 + k; isMeasured(t)) {
          FrozenLod frozen(renderer);
          OlderLod& o = older[t];
          o.images.resize(std::max(o.images.size(), size_t(k - 1)));
          o.images[size_t(k - 2)] = {renderer.settings().width, renderer.settings().height,
                                     renderer.renderImage(pose(t), pose(t), RenderMode::Shaded)};
        }
      RgbaImage before;  // popping: the previous state drawn from this frame's view
      if (measured && f > 0 && ms.on("popping")) {
        FrozenLod frozen(renderer);
        before = {renderer.settings().width, renderer.settings().height,
                  renderer.renderImage(pose(f), pose(f), RenderMode::Shaded)};
      }
      replay.advanceTo(f);
      if (!measured) continue;
      FrozenLod frozen(renderer);
      keep(measureFrame(ctx, renderer, *scheme, renderer.params(), terrain, referenceKey(c), ms, refs, f,
                        pose(std::max(0, f - 1)), pose(f), before.px.empty() ? nullptr : &before, false,
                        older.count(f) ? &older[f] : nullptr));
      older.erase(f);
    }
  } else if (ms.every > 0) {
    for (int f = 0; f < frames; f += ms.every) {
      if (gStop) throw Interrupted();
      OlderLod older;  // popping at lags 2 and 3: the LOD cameras of frames f - 2 and f - 3
      for (int k = 2; k <= kPopLags && f - k >= 0; ++k) older.poses.push_back(pose(f - k));
      keep(measureFrame(ctx, renderer, *scheme, renderer.params(), terrain, referenceKey(c), ms, refs, f,
                        pose(std::max(0, f - 1)), pose(f), nullptr, false, &older));
    }
  }
  // The LOD's lag behind the camera over every frame of the path (replay/settle.h).
  if (ms.on("error")) {
    const auto settleStart = std::chrono::steady_clock::now();
    result.settle =
        stateful ? settleJson(settleSeries(renderer, pose, frames, timedLod), "updates") : settledByCamera(frames);
    // Its cost spread over the measured frames, as the GPU path's setup is (measure_costs_ms.passes.settle).
    const double settleS = secondsSince(settleStart);
    for (FrameMetrics& m : result.metrics)
      if (stateful) m.costs["settle"] = settleS / double(result.metrics.size());
  }
  if (progress) progress->phase(Phase::Images);

  // Images for people are separate passes after the timed and measured frames, never inside them
  // (replay/case_images.h): the configured frames and the worst measured ones.
  if (!config.images.modes.empty()) {
    json worst = result.metrics.empty() ? json() : caseSummary(result).value("worst_frames", json());
    CaseImageInputs in{ctx, c, config, *scheme, renderer, terrain, referenceKey(c), refs, pose, imageDir, timedLod};
    result.images = writeCaseImages(in, imageFrames(config.images, frames, worst), kept);
  }
  // What the case's renderer holds at its end: the instance records grown to the path's largest
  // selection, the captures to the largest measured frame.
  const GpuMemoryAccount memory = renderer.gpuMemory();
  result.memory = memoryJson(&memory, "", hostPeak(hostPeakReset));
  result.seconds = secondsSince(t0);
  return result;
}

}  // namespace lb
