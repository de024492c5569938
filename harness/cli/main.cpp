// lodbench: command-line entry point. Subcommands: list, devices, run, render, merge, report,
// compare, ab, gbench, probe.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "camera/camera_path.h"
#include "cli/dry_run.h"
#include "cli/list.h"
#include "cli/load_bench.h"
#include "cli/probe_command.h"
#include "compare/commands.h"
#include "compare/suite_verdict.h"
#include "config/config.h"
#include "did_you_mean.h"
#include "error.h"
#include "metrics/cracks.h"
#include "number_text.h"
#include "render/image_io.h"
#include "render/renderer.h"
#include "render/terrain_fit.h"
#include "replay/lod_replay.h"
#include "replay/measure.h"
#include "report/report.h"
#include "results/gbench_json.h"
#include "schemes/plugins.h"
#include "schemes/registry.h"
#include "sha256.h"
#include "sweep/merge.h"
#include "sweep/runner.h"
#include "terrain/heightfield.h"
#include "terrain/terrain_shape.h"
#include "version.h"
#include "vk/context.h"

using namespace lb;

static int listSchemes() {
  // The controls last, in the same columns (their descriptions say what they are).
  std::vector<const Scheme*> schemes = allSchemes();
  schemes.insert(schemes.end(), controlSchemes().begin(), controlSchemes().end());
  std::fputs(schemeListing(schemes).c_str(), stdout);
  return 0;
}

constexpr int kDevicesPage = 1023;

static int listDevicesCmd() {
  for (auto& d : listDevices()) {
    std::printf("[%d] %s: %s\n", d.index, d.name.c_str(), d.suitable ? "suitable" : d.rejectReason.c_str());
    if (d.cpu)  // its timings measure the host's cores, not a GPU
      std::printf(
          "    CPU software rasterizer (VK_PHYSICAL_DEVICE_TYPE_CPU): counters are exact, timings are of this "
          "machine's CPU cores, not of a GPU\n");
    const DeviceLimits& l = d.limits;
    const int side = largestSquareTerrain(l);
    std::printf(
        "    largest terrain: %d x %d samples (maxImageDimension2D %u, largest allocation %llu MiB, "
        "%s heap %llu MiB)\n",
        side, side, l.maxImageDimension2D, (unsigned long long)(l.maxAllocationBytes >> 20),
        l.sharedHeap ? "one" : "device-local", (unsigned long long)(l.deviceHeapBytes >> 20));
    // In pages of 1023 cells (4 MiB each, docs/tiled-heightfield.md): the terrain's "page".
    const int tiled = largestSquareTiledTerrain(l, kDevicesPage);
    std::printf(
        "    largest terrain in pages of %d cells: %d x %d samples (maxImageArrayLayers %u; heights and normal "
        "map in pages)\n",
        kDevicesPage, tiled, tiled, l.maxImageArrayLayers);
    std::printf("    %s\n", meshShaderLine(d.mesh).c_str());
  }
  return 0;
}

struct RenderArgs {
  std::string scheme = "sphere", path, out = "frame.png", device, terrainFile, terrainType = "procedural";
  std::vector<std::string> params;
  int frame = 0, width = 640, height = 360, grid = 32, size = 513;
  int terrainWidth = 0, terrainHeight = 0;  // r16 / r32f: samples per row and rows
  int band = 0, overview = 0;               // gdal (the config's terrain 'band', 'overview', 'window')
  std::vector<int> window;
  bool sizeOrSeedGiven = false;
  unsigned seed = 1;
  int warmup = Config{}.warmupFrames;              // a stateful LOD's warm-up updates, as a run's default
  double fps = 30, extent = -1, heightScale = -1;  // extent < 0: 1000, or gdal's from the file
  bool wireframe = false, heatmap = false, error = false, cracks = false, validation = false;
};

// The terrain a render's flags describe, as a config's "terrain" object would: flags the type does
// not read are errors, not silently ignored.
static TerrainSpec renderTerrain(const RenderArgs& a) {
  TerrainSpec spec;
  spec.type = a.terrainType;
  const bool procedural = spec.type == "procedural", raw = spec.type == "r16" || spec.type == "r32f";
  const bool gdal = spec.type == "gdal";
  if (!procedural && spec.type != "hgt" && spec.type != "png16" && !raw && !gdal)
    throw InputError("--terrain '" + printable(spec.type) + "': not one of procedural, hgt, png16, r16, r32f, gdal");
  if (procedural && !a.terrainFile.empty())
    throw InputError(
        "--terrain-file needs a file terrain type (--terrain hgt|png16|r16|r32f|gdal); procedural terrains are "
        "generated");
  if (!gdal && (a.band != 0 || a.overview != 0 || !a.window.empty()))
    throw InputError("--band, --window and --overview apply to --terrain gdal only");
  if (!procedural && a.terrainFile.empty()) throw InputError("--terrain " + spec.type + " needs --terrain-file FILE");
  if (!procedural && a.sizeOrSeedGiven)
    throw InputError("--size and --seed apply to procedural terrains only (--terrain " + spec.type +
                     " reads its file)");
  if (raw && (a.terrainWidth == 0 || a.terrainHeight == 0))
    throw InputError("--terrain " + spec.type + " needs --terrain-width and --terrain-height (samples per row, rows)");
  if (!raw && (a.terrainWidth != 0 || a.terrainHeight != 0))
    throw InputError("--terrain-width and --terrain-height apply to r16 and r32f only (other types carry their size)");
  spec.file = a.terrainFile;
  spec.size = a.size;
  spec.seed = a.seed;
  spec.rawWidth = a.terrainWidth;
  spec.rawHeight = a.terrainHeight;
  spec.extent = a.extent >= 0 ? float(a.extent) : gdal ? 0.0f : 1000.0f;  // gdal: 0 = from the georeferencing
  spec.band = a.band;
  spec.window = a.window;
  spec.overview = a.overview;
  if (!procedural) spec.heightScale = 1.0f;
  if (a.heightScale >= 0) spec.heightScale = float(a.heightScale);
  return spec;
}

// An output path that cannot be written fails now, not after minutes of rendering.
static void checkOutputFile(const std::string& path, const char* flag) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError(std::string(flag) + " '" + path + "' is a directory; give a file name");
  fs::path dir = fs::path(path).parent_path();
  if (dir.empty()) dir = ".";
  if (!fs::is_directory(dir, ec))
    throw InputError(std::string(flag) + " '" + path + "': directory '" + dir.string() + "' does not exist");
  if (access(dir.c_str(), W_OK) != 0)
    throw InputError(std::string(flag) + " '" + path + "': directory '" + dir.string() + "' is not writable");
}

static int renderCmd(const RenderArgs& a) {
  const Scheme* scheme = findScheme(a.scheme);
  if (!scheme) throw InputError("--scheme: " + unknownSchemeText(printable(a.scheme)));
  ParamValues given;
  for (auto& kv : a.params) {
    auto eq = kv.find('=');
    if (eq == std::string::npos) throw InputError("--param '" + kv + "': expected name=value");
    try {
      given[kv.substr(0, eq)] = std::stod(kv.substr(eq + 1));
    } catch (const std::exception&) {
      throw InputError("--param '" + kv + "': value is not a number");
    }
  }
  // Everything is checked before the device starts and the frame renders, so a typo costs nothing.
  checkOutputFile(a.out, "--out");
  TerrainSpec spec = renderTerrain(a);
  terrainShape(spec);  // a missing or malformed file fails here; the samples are read once the device takes them
  CameraPath path = loadCameraPath(a.path);
  int frames = frameCount(path, a.fps);
  if (a.frame < 0 || a.frame >= frames)
    throw InputError("--frame " + std::to_string(a.frame) + " is outside the path's " + std::to_string(frames) +
                     " frames");
  Context ctx;
  createContext(ctx, {a.device, a.validation});
  std::unique_ptr<Context, void (*)(Context*)> guard(&ctx, [](Context* c) { destroyContext(*c); });
  checkTerrainFits(deviceLimits(ctx.physicalDevice), spec, spec.file.empty() ? spec.type : spec.file);
  Heightfield terrain = makeHeightfield(spec);
  {
    Renderer renderer(ctx, terrain, {a.width, a.height, a.grid});
    renderer.setScheme(*scheme, given);
    auto poseAt = [&](int f) { return samplePose(path, a.fps, f, terrain); };
    CameraPose pose = poseAt(a.frame);
    // A stateful LOD (cbt) draws what the run's frame drew: its history from the path's first pose
    // (converge, warm up, the updates of frames 0 ... frame), frozen there (replay/lod_replay.h).
    std::unique_ptr<FrozenLod> frozen;
    if (renderer.statefulLod()) {
      startLod(renderer, poseAt(0), a.warmup);
      LodReplay replay(renderer, poseAt, {});
      replay.advanceTo(a.frame);
      frozen = std::make_unique<FrozenLod>(renderer);
    }
    RenderMode mode = a.wireframe ? RenderMode::Wireframe : a.heatmap ? RenderMode::Heatmap : RenderMode::Shaded;
    FrameResult fr;
    renderer.setSky(true);  // an image for people; the measurement passes below need the magenta
    auto px = renderer.renderImage(pose, pose, mode, &fr);
    renderer.setSky(false);
    if (a.error || a.cracks) {
      // Error map and crack mask come from the measurement passes of a run.
      MeasureSpec spec;
      spec.every = 1;
      spec.passes = {"error", "cracks"};
      ReferenceCache refs;
      FrameMetrics m =
          measureFrame(ctx, renderer, *scheme, renderer.params(), terrain, "cli", spec, refs, a.frame, pose, pose,
                       nullptr, /*keepPixels=*/true);  // the error map itself, on either measurement path
      px = a.error ? errorImage(m.errorMap, a.width, a.height).px
                   : crackMaskImage({a.width, a.height, px}, m.crackMask).px;  // over the sky-shaded frame
      for (auto& [k, v] : m.values) {
        auto why = m.unavailable.find(k);
        if (!std::isnan(v))
          std::printf("%s = %g\n", k.c_str(), v);
        else
          std::printf("%s = null (%s)\n", k.c_str(),
                      why != m.unavailable.end() ? why->second.c_str() : "not measured on this frame");
      }
    }
    writePng(a.out, a.width, a.height, px);
    std::printf("%s: %s frame %d on %s: %llu patches, %llu triangles, %.3f ms GPU\n", a.out.c_str(), a.scheme.c_str(),
                a.frame, ctx.props.deviceName, (unsigned long long)fr.stats.tcsPatches,
                (unsigned long long)fr.stats.clipInvocations, fr.gpuMs);
  }
  return ctx.validationErrors > 0 ? 3 : 0;
}

// A run's report and merge read its plugin schemes' draw paths, counters and main parameters:
// the libraries run.json names are loaded again where they are still there, unchanged.
static void loadRunPlugins(const std::string& runDir) {
  std::ifstream f(runDir + "/run.json");
  const nlohmann::json run = nlohmann::json::parse(f, nullptr, false);
  if (run.is_discarded() || !run.contains("context") || !run["context"].contains("plugins")) return;
  for (const nlohmann::json& p : run["context"]["plugins"]) {
    const std::string file = p.value("file", ""), digest = p.value("sha256", "");
    std::string why;
    try {
      if (!std::filesystem::is_regular_file(file))
        why = "it is gone";
      else if (sha256File(file) != digest)
        why = "it changed since the run (sha256 " + digest.substr(0, 8) + " -> " + sha256File(file).substr(0, 8) + ")";
      else
        loadPlugin(file);
    } catch (const std::exception& e) {
      why = e.what();
    }
    if (!why.empty())
      std::fprintf(stderr,
                   "lodbench: note: plugin %s of this run not loaded: %s; its schemes are named without their "
                   "draw path, counters or main parameter (give the run's build with --plugin)\n",
                   file.c_str(), why.c_str());
  }
}

// CLI11's Range lets NaN through (every comparison with it is false) and prints its bounds with
// std::to_string ("not in range 0.000000 to 1.000000"), hence this check for floating-point flags.
static CLI::Validator finite(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& v) -> std::string {
        double d = 0;
        try {
          size_t used = 0;
          d = std::stod(v, &used);
          if (used != v.size()) return "'" + printable(v) + "' is not a number";
        } catch (const std::exception&) {
          return "'" + printable(v) + "' is not a number";
        }
        if (!std::isfinite(d) || d < lo || d > hi)
          return printable(v) + " is outside [" + numberText(lo) + ", " + numberText(hi) + "]";
        return "";
      },
      "FINITE");
}

int main(int argc, char** argv) {
  CLI::App app{"lodbench: compare GPU terrain level-of-detail schemes on one Vulkan tessellation renderer"};
  app.require_subcommand(1);
  app.set_version_flag("--version", kToolVersion);
  std::vector<std::string> pluginFiles;
  app.add_option("--plugin", pluginFiles,
                 "Scheme library to load (repeatable; docs/plugins.md): its schemes join every command like "
                 "built-in ones. Given before or after the subcommand")
      ->allow_extra_args(false);  // one file per --plugin, so `--plugin a.so run c.json` leaves `run` alone
  app.fallthrough();  // `lodbench run c.json --plugin lib.so` as well as `lodbench --plugin lib.so run c.json`

  auto* list = app.add_subcommand("list", "List LOD schemes with their parameters, defaults and ranges");
  auto* devices = app.add_subcommand("devices", "List Vulkan devices and why each is or is not suitable");

  auto* run = app.add_subcommand("run", "Run a benchmark config: every case, results to results/<name>/<run-id>/");
  std::string configFile;
  RunOptions ro;
  std::string runDevice;
  bool quiet = false;
  run->add_option("config", configFile, "Config file (JSON), e.g. configs/quick.json")->required();
  run->add_option("--out", ro.outDir,
                  "Run directory (an existing one is resumed or grown: finished cases with unchanged inputs are kept, "
                  "new cases run)");
  run->add_option("--device", runDevice, "Vulkan device: name substring or index (overrides the config)");
  run->add_flag("--validation", ro.validation, "Enable the Vulkan validation layer");
  run->add_flag("-q,--quiet", quiet, "No progress output");
  std::string shard;
  bool dryRun = false;
  run->add_option("--shard", shard,
                  "Run the deterministic subset i/n of the cases: the i-th of n contiguous blocks of whole workloads "
                  "(terrain, path, resolution, grid), or of cases when there are fewer workloads than shards");
  run->add_flag("--dry-run", dryRun,
                "List the cases (of this shard) with their count, estimated time and disk, and exit; opens no device");
  run->add_flag("--rerun-changed", ro.rerunChanged,
                "Resume: rerun finished cases whose inputs (files, settings) changed instead of refusing");

  auto* merge = app.add_subcommand("merge", "Join shard run directories into one run");
  std::string mergeOut;
  std::vector<std::string> mergeInputs;
  bool mergeForce = false;
  merge->add_option("--out", mergeOut, "Merged run directory (not one of the runs)")->required();
  merge->add_option("runs", mergeInputs, "Shard run directories, in any order; one named twice counts once")
      ->required();
  merge->add_flag("--force", mergeForce,
                  "Merge runs of different configs, tool versions, devices or drivers (never two differing copies "
                  "of a case)");
  merge->footer(
      "Copies of a case (same case id) in several folders, as a retried shard leaves them: byte-identical\n"
      "copies (case file and its images) are kept once; a finished (ok) copy is kept over failed or skipped\n"
      "ones; two finished copies that differ in any byte (a case measured twice: other timings) are refused,\n"
      "exit 2, naming the case and both folders: leave a folder out or delete one copy. Unfinished copies\n"
      "that differ: the first folder's by name. The output depends only on the set of folders: merging\n"
      "them again, in any order, gives the same bytes (docs/results-format.md, Merging shards).");
  double testSlowdown = 0;
  run->add_option("--test-slowdown", testSlowdown,
                  "Testing only: redraw this fraction of the patches inside the timed region (planted regression)")
      ->check(finite(0, 1))
      ->group("Testing");

  auto* render = app.add_subcommand("render", "Render one frame of a camera path to PNG");
  RenderArgs ra;
  render->add_option("--scheme", ra.scheme, "LOD scheme")->capture_default_str();
  render->add_option("--param", ra.params, "Scheme parameter name=value (repeatable)");
  render->add_option("--path", ra.path, "Camera path CSV")->required();
  render->add_option("--frame", ra.frame, "Frame index")->capture_default_str();
  render->add_option("--fps", ra.fps, "Path sampling rate (frames per second)")
      ->capture_default_str()
      ->check(finite(1, 1000));
  render
      ->add_option("--warmup", ra.warmup,
                   "Stateful schemes (cbt): warm-up updates at the first pose before the path, as the "
                   "run's warmup_frames")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  render->add_option("--out", ra.out, "Output PNG")->capture_default_str();
  render->add_option("--width", ra.width, "Image width")->capture_default_str()->check(CLI::Range(16, 8192));
  render->add_option("--height", ra.height, "Image height")->capture_default_str()->check(CLI::Range(16, 8192));
  render->add_option("--grid", ra.grid, "Patches per side")->capture_default_str()->check(CLI::Range(1, 1024));
  render->add_option("--terrain", ra.terrainType, "procedural | hgt | png16 | r16 | r32f | gdal")
      ->capture_default_str();
  render->add_option("--terrain-file", ra.terrainFile, "Heightmap file for non-procedural terrains");
  render->add_option("--terrain-width", ra.terrainWidth, "r16 / r32f: samples per row (the config's terrain 'width')")
      ->check(CLI::Range(2, 65536));
  render->add_option("--terrain-height", ra.terrainHeight, "r16 / r32f: number of rows (the config's terrain 'height')")
      ->check(CLI::Range(2, 65536));
  render->add_option("--size", ra.size, "Procedural terrain samples per side")
      ->capture_default_str()
      ->check(CLI::Range(2, 16385));
  render->add_option("--seed", ra.seed, "Procedural terrain seed")->capture_default_str();
  render
      ->add_option("--extent", ra.extent,
                   "World extent of the terrain (default 1000; gdal: from the file's georeferencing)")
      ->check(finite(1e-3, 1e9));
  render->add_option("--band", ra.band, "gdal: raster band, 1-based (needed for a multi-band file)")
      ->check(CLI::Range(1, 65535));
  render->add_option("--window", ra.window, "gdal: X Y W H pixel rectangle to read")->expected(4);
  render->add_option("--overview", ra.overview, "gdal: the file's overview level k (else a 2^k average)")
      ->check(CLI::Range(1, 30));
  render
      ->add_option(
          "--height-scale", ra.heightScale,
          "Height scale (procedural: peak height, default 120; files: multiplier on the stored values, default 1)")
      ->check(finite(0, 1e9));
  render->add_option("--device", ra.device, "Vulkan device: name substring or index");
  render->add_flag("--validation", ra.validation, "Enable the Vulkan validation layer");
  auto* modes = render->add_option_group("mode", "Image mode (default: shaded)");
  modes->add_flag("--wireframe", ra.wireframe, "Wireframe, coloured by tessellation level");
  modes->add_flag("--heatmap", ra.heatmap, "Tessellation level heat map (log2: blue 1, green 8, red 64)");
  modes->add_flag("--error", ra.error, "Screen-space geometric error map (black 0 px .. white >= 8 px, sqrt scale)");
  modes->add_flag("--cracks", ra.cracks, "Crack mask against the reference scheme (red over a dimmed frame)");
  modes->require_option(0, 1);

  auto* report = app.add_subcommand("report", "Report a run: report.md, Vega-Lite charts and (with Node) report.html");
  ReportOptions rep;
  bool noHtml = false;
  report->add_option("run-dir", rep.runDir, "Run directory, e.g. results/quick/<run-id>")->required();
  report->add_option("--out", rep.outDir, "Report directory (default: <run-dir>/report)");
  report->add_option("--frames", rep.frames, "Frames for the image strips, e.g. 0,240 (default: all with images)")
      ->delimiter(',');
  report->add_flag("--no-html", noHtml, "Write Markdown and chart specs only (do not run report/render.mjs)");
  report->add_flag("--self-contained", rep.selfContained,
                   "Embed the run's images in report.html: one file to send, many times larger (prints its size)");
  // compare / ab / gbench (docs/design.md, Reports and regression checks): regression checks and Google Benchmark JSON.
  auto* compare = app.add_subcommand("compare", "Check a candidate run against a baseline; exit 1 on a regression");
  std::string baselineDir;
  std::vector<std::string> candidateDirs;
  compare->add_option("baseline", baselineDir, "Baseline run directory, e.g. results/baseline/ci")->required();
  compare->add_option("candidate", candidateDirs, "Candidate run directory; several = rounds of one config, pooled")
      ->required();
  auto* ab =
      app.add_subcommand("ab", "Run one config with two lodbench binaries interleaved (A B B A A B ...) and compare");
  AbOptions abo;
  ab->add_option("--baseline", abo.baseline, "lodbench binary A (baseline)")->required();
  ab->add_option("--candidate", abo.candidate, "lodbench binary B (candidate)")->required();
  ab->add_option("config", abo.config, "Config file both binaries run")->required();
  ab->add_option("--rounds", abo.rounds, "Runs per binary")->capture_default_str()->check(CLI::Range(1, 1000));
  ab->add_option("--out", abo.outDir, "Directory for the rounds (default results/ab/<time>)");
  CompareOptions co;
  VerdictFiles vf;
  for (CLI::App* sub : {compare, ab}) {
    sub->add_option("--threshold", co.threshold, "Timing regression when slower than 1 + threshold (and significant)")
        ->capture_default_str()
        ->check(finite(0, HUGE_VAL));
    sub->add_option("--alpha", co.alpha, "Significance level of the timing test (t-test on the rounds)")
        ->capture_default_str()
        ->check(finite(1e-9, 0.5));
    sub->add_option("--error-tolerance", co.errorTolerance, "Relative worsening of accuracy metrics allowed")
        ->capture_default_str()
        ->check(finite(0, HUGE_VAL));
    sub->add_flag("--require-exact", co.requireExact,
                  "Counters that cannot be compared (other device or driver) are an error (exit 2), not a pass");
    sub->add_option("--json", vf.json, "Write the verdict as JSON");
    sub->add_option("--md", vf.md, "Write the verdict as Markdown");
  }
  auto* verdict = app.add_subcommand(
      "verdict", "Each scheme's cost ratio to every workload's cheapest with intervals: <run-dir>/verdict.json");
  std::vector<std::string> verdictDirs;
  double verdictConfidence = 0.95;
  verdict->add_option("runs", verdictDirs, "Run directories (each gets its own verdict.json)")->required();
  verdict->add_option("--confidence", verdictConfidence, "Interval confidence")
      ->capture_default_str()
      ->check(finite(0.5, 0.999));
  double verdictMargin = 0;
  verdict
      ->add_option("--margin", verdictMargin,
                   "Practical significance: a scheme within this fraction of the cheapest (its interval's lower "
                   "bound at most 1 + margin) ties it; 0.02 reads 'within 2 % is a tie'")
      ->check(finite(0.0, 1.0));
  auto* gbench = app.add_subcommand("gbench", "Write <run-dir>/gbench.json in Google Benchmark's JSON schema");
  std::string gbenchDir;
  gbench->add_option("run-dir", gbenchDir, "Run directory")->required();

  // probe: the minimal tessellation loop beside lodbench's renderer.
  auto* probe = app.add_subcommand(
      "probe", "Time the minimal tessellation loop (uniform levels) at a config's grid, resolutions, modes and camera");
  ProbeCommandOptions po;
  probe->add_option("config", po.config, "Config file (grid, resolutions, timing modes, terrain, first path)")
      ->required();
  probe->add_option("--device", po.device, "Vulkan device: name substring or index (overrides the config)");
  probe->add_option("--levels", po.levels, "Uniform levels (default: the first scheme's level, else 1)")
      ->delimiter(',');
  probe->add_option("--modes", po.modes, "Timing modes (default: the config's \"timing\")")->delimiter(',');
  probe
      ->add_option("--draw-path", po.drawPath,
                   "tessellation: the tessellated minimal loop and `uniform`; instanced: the same triangles "
                   "pre-tessellated and instanced, against the renderer's instanced path")
      ->capture_default_str()
      ->check(CLI::IsMember({"tessellation", "instanced"}));
  probe->add_flag(
      "--vertex-height", po.vertexHeight,
      "Attribution variant: the minimal loop's vertex shader fetches control-point heights as lodbench's does");
  probe->add_option("--frames", po.frames, "Timed frames per row (median)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  probe->add_option("--warmup", po.warmup, "Unrecorded frames before each row")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  probe->add_option("--frame", po.frame, "Camera: this frame of the config's first path")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  probe->add_flag("--compare", po.compare,
                  "Also time lodbench's renderer (uniform scheme) per row: ratio = minimal / lodbench");
  probe->add_option("--split", po.split, "Split draws like the renderer: auto (lavapipe only), on, off")
      ->capture_default_str();
  probe->add_option("--out", po.out, "Write the JSON here too");
  probe->add_flag("--append", po.append, "Append rows to the --out file");

  // load-bench: what a terrain costs before the first frame, stage by stage (cli/load_bench.h).
  auto* loadBench = app.add_subcommand("load-bench",
                                       "Time loading a config's terrains and their preprocessing (normal map, each "
                                       "scheme's), with peak memory, as JSON");
  LoadBenchOptions lbo;
  loadBench->add_option("config", lbo.config, "Config file (terrains, grid, schemes and their first parameter variant)")
      ->required();
  loadBench->add_option("--out", lbo.out, "Write the JSON here too");
  loadBench->add_option("--threads", lbo.threads, "Threads for the terrain passes (default: all hardware threads)")
      ->check(CLI::Range(1, 1024));
  loadBench->add_option("--write-r32f", lbo.writeR32f,
                        "Also write the first terrain's heights as raw little-endian float32 (for GDAL)");

  // CLI11 answers a mistyped subcommand with "A subcommand is required"; say what is wrong instead.
  if (argc < 2) {
    app.name("lodbench");
    std::printf("%s", app.help().c_str());
    return 2;
  }
  if (argv[1][0] != '-') {
    std::string known;
    std::vector<std::string> names;
    bool found = false;
    const CLI::App& constApp = app;  // the const overload lists every subcommand, parsed or not
    for (const CLI::App* sub : constApp.get_subcommands([](const CLI::App*) { return true; })) {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      names.push_back(sub->get_name());
      found = found || sub->get_name() == argv[1];
    }
    if (!found) {
      std::fprintf(stderr, "lodbench: error: unknown subcommand '%s' (known: %s; see lodbench --help)%s\n",
                   printable(argv[1]).c_str(), known.c_str(), didYouMean(argv[1], names).c_str());
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  ra.sizeOrSeedGiven = render->count("--size") + render->count("--seed") > 0;
  try {
    for (const std::string& file : pluginFiles) try {
        loadPlugin(file);
      } catch (const InputError& e) {
        throw InputError(std::string("--plugin: ") + e.what());
      }
    if (*report) loadRunPlugins(rep.runDir);
    if (*merge)
      for (const std::string& dir : mergeInputs) loadRunPlugins(dir);
    if (*list) return listSchemes();
    if (*devices) return listDevicesCmd();
    if (*render) return renderCmd(ra);
    if (*compare) return compareCommand(baselineDir, candidateDirs, co, vf);
    if (*verdict) return verdictCommand(verdictDirs, verdictConfidence, verdictMargin);
    if (*ab) return abCommand(abo, co, vf);
    if (*probe) return probeCommand(po);
    if (*loadBench) return loadBenchCommand(lbo);
    if (*gbench) {
      std::printf("%s\n", writeGoogleBenchmarkJson(gbenchDir).c_str());
      return 0;
    }
    if (*merge) {
      MergeTotals t = mergeRuns(mergeOut, mergeInputs, mergeForce);
      for (auto& n : t.notes) std::fprintf(stderr, "lodbench: merge: %s\n", n.c_str());
      std::printf("%s\n", mergeOut.c_str());
      std::fprintf(stderr, "lodbench: merged %d cases (%d duplicates left out) from %d runs -> %s\n", t.cases,
                   t.duplicates, t.folders, mergeOut.c_str());
      return 0;
    }
    if (*report) {
      rep.html = !noHtml;
      // The report opens with the run's verdict (compare/suite_verdict.h), written beside it first.
      // A verdict already there keeps the confidence and margin it was asked with.
      if (std::filesystem::exists(std::filesystem::path(rep.runDir) / "run.json")) try {
          double confidence = 0.95, margin = 0;
          const std::filesystem::path earlier = std::filesystem::path(rep.runDir) / "verdict.json";
          if (std::filesystem::exists(earlier)) {
            std::ifstream in(earlier);
            const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
            if (j.is_object()) {
              confidence = j.value("confidence", confidence);
              margin = j.value("margin", margin);
            }
          }
          writeVerdict(rep.runDir, confidence, margin);
        } catch (const std::exception& e) {
          std::fprintf(stderr, "lodbench: note: no verdict.json: %s\n", e.what());
        }
      return reportCommand(rep);
    }
    if (*run) {
      Config config = loadConfig(configFile);
      if (!runDevice.empty()) {  // the flag overrides the config, and its message names the flag
        config.device = runDevice;
        config.deviceWhere.clear();
      }
      config.testSlowdown = testSlowdown;
      if (!shard.empty()) parseShard(shard, ro.shardIndex, ro.shardCount);
      if (dryRun) return lb::dryRun(config, ro.outDir, ro.shardIndex, ro.shardCount, !shard.empty());
      ro.progress = !quiet;
      // An unmatched --device (or a missing validation layer) must fail before runSweep creates the run directory.
      checkContextOptions({config.device, ro.validation, config.deviceWhere});
      // Ctrl-C / kill: finish the current frame, keep every finished case, exit 130.
      std::signal(SIGINT, [](int) { requestStop(); });
      std::signal(SIGTERM, [](int) { requestStop(); });
      RunTotals t = runSweep(config, ro);
      if (t.interrupted) {
        std::fprintf(stderr, "lodbench: interrupted; %d finished cases kept in %s (run again to resume)\n", t.ok,
                     t.dir.c_str());
        return 130;
      }
      std::printf("%s\n", t.dir.c_str());
      std::fprintf(stderr, "lodbench: %d ok (%d resumed), %d failed, %d skipped -> %s\n", t.ok, t.resumed, t.failed,
                   t.skipped, t.dir.c_str());
      return t.failed > 0 ? 1 : 0;
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "lodbench: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lodbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
