#include "sweep/runner.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "camera/camera_path.h"
#include "error.h"
#include "render/image_io.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "vk/context.h"

namespace lb {

namespace fs = std::filesystem;
using nlohmann::json;

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

CaseResult runCase(Context& ctx, const Case& c, const Config& config, const std::string& imageDir, bool progress) {
  auto t0 = std::chrono::steady_clock::now();
  CaseResult result;
  const Scheme* scheme = findScheme(c.scheme);
  if (!scheme) throw InputError("unknown scheme '" + c.scheme + "'");
  Heightfield terrain = makeHeightfield(c.terrain);
  CameraPath path = loadCameraPath(c.path);
  RenderSettings settings{c.width, c.height, config.grid, config.testSlowdown};
  Renderer renderer(ctx, terrain, settings);
  renderer.setScheme(*scheme, c.params);
  int frames = frameCount(path, config.fps);
  if (config.maxFrames > 0) frames = std::min(frames, config.maxFrames);
  auto pose = [&](int f) { return samplePose(path, config.fps, f, terrain); };

  // Warm-up: the first pose, unrecorded, so caches, clocks and pipelines settle.
  for (int i = 0; i < config.warmupFrames; ++i) renderer.submitFrame(-1, pose(0), pose(0));
  renderer.finish();
  renderer.takeCompleted();

  int total = frames * config.repetitions;
  for (int rep = 0; rep < config.repetitions; ++rep)
    for (int f = 0; f < frames; ++f) {
      CameraPose p = pose(f);
      renderer.submitFrame(f, p, p);
      for (auto& r : renderer.takeCompleted()) result.frames.push_back(r);
      int done = rep * frames + f + 1;
      // On a terminal the line updates in place; in logs, one line per tenth of the case.
      bool tty = isatty(fileno(stderr));
      if (progress && (tty ? done % 10 == 0 || done == total : done % std::max(1, total / 10) == 0)) {
        double el = secondsSince(t0);
        std::fprintf(stderr, "%s    frame %d/%d  %.1fs elapsed, ~%.0fs left%s", tty ? "\r" : "", done, total, el,
                     el / done * (total - done), tty ? "   " : "\n");
        std::fflush(stderr);
      }
    }
  renderer.finish();
  for (auto& r : renderer.takeCompleted()) result.frames.push_back(r);

  // Images are separate passes after the timed frames, never inside them.
  for (int f : config.images.frames) {
    int frame = f < 0 ? frames + f : f;
    if (frame < 0 || frame >= frames) continue;
    for (auto& modeName : config.images.modes) {
      RenderMode mode = parseRenderMode(modeName);
      if (mode == RenderMode::Wireframe && !ctx.enabledFeatures.fillModeNonSolid) continue;
      auto px = renderer.renderImage(pose(frame), pose(frame), mode);
      std::string name = c.id + "_f" + std::to_string(frame) + "_" + modeName + ".png";
      writePng(imageDir + "/" + name, c.width, c.height, px);
      result.images.push_back("images/" + name);
    }
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

// frames.csv and summary.json are rebuilt from the case files, so resumed runs stay complete.
static void writeAggregates(const std::string& dir, const json& context) {
  std::string csv = framesCsvHeader();
  json cases = json::array();
  std::vector<fs::path> files;
  for (auto& e : fs::directory_iterator(dir + "/cases"))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (auto& file : files) {
    std::ifstream in(file);
    json cj = json::parse(in, nullptr, false);
    if (cj.is_discarded()) continue;
    cases.push_back({{"case_id", cj["case_id"]}, {"scheme", cj["scheme"]}, {"params", cj["params"]},
                     {"terrain", cj["terrain"]["label"]}, {"path", cj["path"]}, {"resolution", cj["resolution"]},
                     {"status", cj["status"]}, {"reason", cj["reason"]}, {"summary", cj["summary"]}});
    for (auto& f : cj["frames"])
      csv += cj["case_id"].get<std::string>() + "," + f["frame"].dump() + "," + f["gpu_ms"].dump() + "," +
             f["cpu_ms"].dump() + "," + f["patches"].dump() + "," + f["tes_invocations"].dump() + "," +
             f["clip_invocations"].dump() + "," + f["clip_primitives"].dump() + "," +
             f["fragment_invocations"].dump() + "\n";
  }
  writeFileAtomic(dir + "/frames.csv", csv);
  json summary = {{"schema_version", kSchemaVersion}, {"context", context}, {"cases", cases}};
  writeFileAtomic(dir + "/summary.json", summary.dump(2));
}

RunTotals runSweep(const Config& config, const RunOptions& options) {
  RunTotals totals;
  totals.dir = options.outDir.empty() ? defaultRunDir(config) : options.outDir;
  fs::create_directories(totals.dir + "/cases");
  fs::create_directories(totals.dir + "/images");
  Context ctx;
  createContext(ctx, {config.device, options.validation});
  std::unique_ptr<Context, void (*)(Context*)> guard(&ctx, [](Context* c) { destroyContext(*c); });
  json context = runContext(ctx, config);
  std::string runJson = totals.dir + "/run.json";
  json run = {{"schema_version", kSchemaVersion}, {"context", context}, {"start_time", context["time"]}};
  if (config.testSlowdown > 0) run["test_slowdown"] = config.testSlowdown;  // so no one mistakes it for data
  writeFileAtomic(runJson, run.dump(2));

  auto cases = expandCases(config);
  auto t0 = std::chrono::steady_clock::now();
  if (options.progress)
    std::fprintf(stderr, "lodbench: %zu cases on %s -> %s\n", cases.size(), ctx.props.deviceName, totals.dir.c_str());
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    std::string caseFile = totals.dir + "/cases/" + c.id + ".json";
    if (std::ifstream in{caseFile}) {
      json old = json::parse(in, nullptr, false);
      if (!old.is_discarded() && old.value("status", "") == "ok") {
        totals.resumed++;
        totals.ok++;
        continue;
      }
    }
    if (options.progress) {
      double el = secondsSince(t0);
      std::fprintf(stderr, "[%zu/%zu] %s  (%.0fs elapsed)\n", i + 1, cases.size(), c.id.c_str(), el);
    }
    CaseResult r;
    try {
      r = runCase(ctx, c, config, totals.dir + "/images", options.progress);
    } catch (const std::exception& e) {
      r.status = "failed";
      r.reason = e.what();
    }
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
  run["totals"] = {{"ok", totals.ok}, {"failed", totals.failed}, {"skipped", totals.skipped}, {"cases", cases.size()}};
  run["validation_errors"] = ctx.validationErrors.load();
  writeFileAtomic(runJson, run.dump(2));
  writeAggregates(totals.dir, context);
  totals.validationErrors = ctx.validationErrors.load();
  return totals;
}

}  // namespace lb
