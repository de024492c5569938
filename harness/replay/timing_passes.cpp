// Timing-mode replays, their counter cross-check, and clock-control calibration.
#include "replay/timing_passes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "camera/camera_path.h"
#include "error.h"
#include "render/lod_state.h"
#include "schemes/registry.h"
#include "stats.h"
#include "vk/context.h"

namespace lb {

RenderMode timingRenderMode(const std::string& name) {
  if (name == "shaded") return RenderMode::Shaded;
  if (name == "depth") return RenderMode::Depth;
  if (name == "frontend") return RenderMode::Frontend;
  throw InputError("unknown timing mode '" + name + "' (shaded, depth, frontend)");
}

std::vector<FrameResult> replayInMode(Renderer& renderer, RenderMode mode, int frames, int repetitions, int warmup,
                                      const std::function<CameraPose(int)>& pose) {
  for (int i = 0; i < warmup; ++i) renderer.submitFrame(-1, pose(0), pose(0), mode);
  renderer.finish();
  renderer.takeCompleted();
  std::vector<FrameResult> out;
  for (int rep = 0; rep < repetitions; ++rep)
    for (int f = 0; f < frames; ++f) {
      if (f == 0 && renderer.statefulLod()) renderer.lodState().restore();  // S0, as the shaded pass
      CameraPose p = pose(f);
      renderer.submitFrame(f, p, p, mode);
      for (auto& r : renderer.takeCompleted()) out.push_back(r);
    }
  renderer.finish();
  for (auto& r : renderer.takeCompleted()) out.push_back(r);
  return out;
}

std::string compareTessellationCounters(const std::vector<FrameResult>& shaded, const std::vector<FrameResult>& other,
                                        const std::string& mode) {
  if (shaded.size() != other.size())
    return mode + ": " + std::to_string(other.size()) + " frames, shaded has " + std::to_string(shaded.size());
  for (size_t i = 0; i < shaded.size(); ++i) {
    const PipelineStats &a = shaded[i].stats, &b = other[i].stats;
    const std::pair<const char*, std::pair<uint64_t, uint64_t>> counters[] = {
        {"ia_vertices", {a.iaVertices, b.iaVertices}},
        {"ia_primitives", {a.iaPrimitives, b.iaPrimitives}},
        {"vs_invocations", {a.vsInvocations, b.vsInvocations}},
        {"patches", {a.tcsPatches, b.tcsPatches}},
        {"tes_invocations", {a.tesInvocations, b.tesInvocations}},
        {"task_invocations", {a.taskInvocations, b.taskInvocations}},
        {"mesh_invocations", {a.meshInvocations, b.meshInvocations}},
        {"instances", {shaded[i].instances, other[i].instances}}};
    for (auto& [name, v] : counters)
      if (v.first != v.second)
        return mode + " frame " + std::to_string(shaded[i].frame) + ": " + name + " " + std::to_string(v.second) +
               " != shaded " + std::to_string(v.first);
  }
  return {};
}

bool calibrationStable(const std::vector<double>& runsMs, double tolerance) {
  if (runsMs.size() < 3) return false;
  std::vector<double> last(runsMs.end() - 3, runsMs.end());
  std::sort(last.begin(), last.end());
  return last[1] > 0 && (last[2] - last[0]) / last[1] <= tolerance;
}

static RenderSettings calibrationSettings(RenderSettings s) {
  s.testSlowdown = 0;  // the calibration workload is fixed: never the planted regression
  return s;
}

Calibrator::Calibrator(Context& ctx, const Heightfield& terrain, const RenderSettings& settings, const TimingSpec& spec,
                       const CameraPose& pose)
    : renderer_(ctx, terrain, calibrationSettings(settings)), spec_(spec), pose_(pose) {
  const Scheme& uniform = *schemeWithRole(MainParamRole::UniformLevel);
  renderer_.setScheme(uniform, {{uniform.info().mainParam, spec.level}});
  // One unrecorded run: pipeline creation and first-touch costs are not the clock.
  runOnce();
}

double Calibrator::runOnce() {
  for (int i = 0; i < spec_.frames; ++i) renderer_.submitFrame(i, pose_, pose_);
  renderer_.finish();
  std::vector<double> ms;
  for (auto& f : renderer_.takeCompleted()) ms.push_back(f.gpuMs);
  return summarize(ms).median;
}

CalibrationRun Calibrator::untilStable() {
  CalibrationRun run;
  auto t0 = std::chrono::steady_clock::now();
  auto loaded = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  while (loaded() < spec_.minLoadS) runOnce();
  run.loadS = loaded();
  while (int(run.runsMs.size()) < spec_.maxTries) {
    run.runsMs.push_back(runOnce());
    if (calibrationStable(run.runsMs, spec_.tolerance)) {
      run.stable = true;
      break;
    }
  }
  return run;
}

nlohmann::json calibrationJson(const CalibrationRun& before, double afterMs, const TimingSpec& spec) {
  double b = before.ms(), a = afterMs * (1 + spec.testDrift);
  double drift = b > 0 ? a / b - 1 : NAN;
  nlohmann::json j = {{"controlled", true},
                      {"level", spec.level},
                      {"frames", spec.frames},
                      {"before_ms", b},
                      {"after_ms", a},
                      {"before_runs", before.runsMs},
                      {"load_s", before.loadS},
                      {"stable_before", before.stable},
                      {"drift", std::isfinite(drift) ? nlohmann::json(drift) : nlohmann::json(nullptr)},
                      {"flagged", !std::isfinite(drift) || std::abs(drift) > spec.driftLimit}};
  if (spec.testDrift != 0) j["test_drift"] = spec.testDrift;  // so no one mistakes it for data
  return j;
}

bool cpuRasterizer(const Context& ctx) {
  const char* fake = std::getenv("LODBENCH_TEST_DEVICE_TYPE");
  if (fake && std::string(fake) == "gpu") return false;
  return ctx.props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
}

bool calibrationWanted(const TimingSpec& spec, const Context& ctx) {
  return spec.calibrateSet ? spec.calibrate : !cpuRasterizer(ctx);
}

nlohmann::json uncalibratedJson(const TimingSpec& spec, const Context& ctx) {
  const bool cpu = cpuRasterizer(ctx);
  std::string reason = cpu ? "a CPU rasterizer: no GPU clock to control"
                           : "clock not controlled: \"calibration\": false in the config, on a GPU whose clock may "
                             "be anywhere between idle and boost";
  if (cpu && spec.calibrateSet) reason += " (and \"calibration\": false in the config)";
  return {{"controlled", false}, {"reason", reason}, {"flagged", !cpu}};
}

}  // namespace lb
