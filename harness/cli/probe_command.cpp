// The probe subcommand: rows of minimal-loop (and lodbench) GPU times as JSON.
#include "cli/probe_command.h"

#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "camera/camera_path.h"
#include "config/config.h"
#include "error.h"
#include "render/probe.h"
#include "render/uniform_instanced.h"
#include "replay/timing_passes.h"
#include "results/write.h"
#include "schemes/registry.h"
#include "stats.h"
#include "terrain/heightfield.h"
#include "vk/context.h"

namespace lb {

using nlohmann::json;

// lodbench's side of a row: the renderer's timed-frame loop at one pose, uniform `level`.
static double lodbenchMedian(Renderer& r, RenderMode mode, const CameraPose& pose, int warmup, int frames,
                             PipelineStats& stats) {
  auto same = [&](int) { return pose; };
  auto done = replayInMode(r, mode, frames, 1, warmup, same);
  std::vector<double> ms;
  for (auto& f : done) ms.push_back(f.gpuMs);
  if (!done.empty()) stats = done.back().stats;
  return summarize(ms).median;
}

int probeCommand(const ProbeCommandOptions& o) {
  Config config = loadConfig(o.config);
  if (!o.device.empty()) {
    config.device = o.device;
    config.deviceWhere.clear();  // --device's own
  }
  if (config.terrains.empty() || config.paths.empty())
    throw InputError(o.config + ": probe needs a terrain and a path");
  if (o.split != "auto" && o.split != "on" && o.split != "off")
    throw InputError("--split '" + o.split + "': expected auto, on or off");
  // The probe's workload: one level everywhere, from the scheme whose main parameter is that level.
  const Scheme* uniform = schemeWithRole(MainParamRole::UniformLevel);
  const std::string& levelParam = uniform->info().mainParam;
  std::vector<int> levels = o.levels;
  if (levels.empty()) {
    levels.push_back(1);
    if (!config.schemes.empty() && !config.schemes[0].variants.empty() &&
        config.schemes[0].variants[0].count(levelParam))
      levels[0] = int(config.schemes[0].variants[0].at(levelParam));
  }
  for (int l : levels)
    if (l < 1 || l > 64) throw InputError("--levels: " + std::to_string(l) + " is outside [1, 64]");
  std::vector<std::string> modes = o.modes.empty() ? config.timing.modes : o.modes;
  for (auto& m : modes) timingRenderMode(m);  // throws InputError for an unknown mode

  Context ctx;
  createContext(ctx, {config.device, false, config.deviceWhere});
  std::unique_ptr<Context, void (*)(Context*)> guard(&ctx, [](Context* c) { destroyContext(*c); });
  Heightfield terrain = makeHeightfield(config.terrains[0]);
  CameraPath path = loadCameraPath(config.paths[0]);
  CameraPose pose = samplePose(path, config.fps, o.frame, terrain);
  bool split = o.split == "on" || (o.split == "auto" && probeNeedsSplit(ctx));
  const bool instanced = o.drawPath == "instanced";
  if (instanced && o.vertexHeight) throw InputError("--vertex-height applies to the tessellated loop only");

  json doc = {{"device", ctx.props.deviceName},
              {"driver", ctx.driverName + " " + ctx.driverInfo},
              {"commit", gitCommit()},
              {"rows", json::array()}};
  if (o.append && !o.out.empty())
    if (std::ifstream in{o.out}) {
      json old = json::parse(in, nullptr, false);
      if (old.is_discarded() || !old.contains("rows")) throw InputError(o.out + ": not a probe file (no rows)");
      if (old.value("device", "") != doc["device"]) throw InputError(o.out + ": rows of another device");
      doc["rows"] = old["rows"];
    }
  for (auto [w, h] : config.resolutions) {
    std::unique_ptr<Renderer> renderer;
    if (o.compare) renderer = std::make_unique<Renderer>(ctx, terrain, RenderSettings{w, h, config.grid});
    for (int level : levels) {
      // The instanced rows compare with the renderer's instanced path drawing the same triangles.
      if (renderer && instanced)
        renderer->setScheme(uniformInstancedScheme(), {{"level", level}, {"diagonal", 2}});
      else if (renderer)
        renderer->setScheme(*uniform, {{levelParam, level}});
      for (const std::string& m : modes) {
        RenderMode mode = timingRenderMode(m);
        json row = {
            {"mode", m}, {"grid", config.grid}, {"level", level}, {"resolution", {w, h}}, {"draw_path", o.drawPath}};
        PipelineStats ls;
        double lodbenchMs = renderer ? lodbenchMedian(*renderer, mode, pose, o.warmup, o.frames, ls) : 0;
        ProbeOptions po;
        po.width = w;
        po.height = h;
        po.grid = config.grid;
        po.level = float(level);
        po.mode = mode;
        po.warmup = o.warmup;
        po.frames = o.frames;
        po.split = split;
        po.vertexHeight = o.vertexHeight;
        po.instanced = instanced;
        ProbeResult p = runProbe(ctx, terrain, pose, po);
        row["minimal_ms"] = p.medianMs;
        row["minimal_draws"] = p.draws;
        if (o.vertexHeight) row["minimal_variant"] = "vertex-height";
        row["frames"] = o.frames;
        row["tes_invocations"] = p.stats.tesInvocations;
        row["triangles"] = p.stats.clipInvocations;
        row["fragment_invocations"] = p.stats.fsInvocations;
        if (renderer) {
          row["lodbench_ms"] = lodbenchMs;
          row["lodbench_draws"] = renderer->drawCount();
          row["ratio"] = lodbenchMs > 0 ? json(p.medianMs / lodbenchMs) : json(nullptr);
          // Same grid, level and camera: the tessellation work must be identical.
          row["counters_equal"] = ls.tcsPatches == p.stats.tcsPatches && ls.tesInvocations == p.stats.tesInvocations &&
                                  (!instanced || ls.clipInvocations == p.stats.clipInvocations);
        } else {
          row["lodbench_ms"] = nullptr;
          row["ratio"] = nullptr;
        }
        std::fprintf(stderr, "probe: %-8s grid %d level %2d %dx%d  minimal %.4f ms%s\n", m.c_str(), config.grid, level,
                     w, h, p.medianMs,
                     renderer ? ("  lodbench " + std::to_string(lodbenchMs) + " ms  ratio " +
                                 std::to_string(lodbenchMs > 0 ? p.medianMs / lodbenchMs : 0))
                                    .c_str()
                              : "");
        doc["rows"].push_back(row);
      }
    }
  }
  std::string text = doc.dump(2);
  if (!o.out.empty()) writeFileAtomic(o.out, text + "\n");
  std::printf("%s\n", text.c_str());
  return 0;
}

}  // namespace lb
