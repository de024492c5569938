// The GPU profiler's timestamp mask, timing modes (depth, frontend) against shaded,
// the minimal loop (probe), and clock-control calibration with a planted drift.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "config/config.h"
#include "error.h"
#include "gpu_fixture.h"
#include "render/probe.h"
#include "render/uniform_instanced.h"
#include "replay/timing_passes.h"
#include "report/report.h"
#include "sweep/runner.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;
namespace fs = std::filesystem;

TEST(GpuProfiler, MaskFollowsTimestampValidBits) {
  EXPECT_EQ(timestampMaskFromValidBits(0), 0u);
  EXPECT_EQ(timestampMaskFromValidBits(64), ~0ull);
  EXPECT_EQ(timestampMaskFromValidBits(36), (1ull << 36) - 1);
  // A counter that wrapped past 2^36 still gives the right difference under the mask.
  uint64_t top = (1ull << 36) - 5, bottom = 7;
  EXPECT_EQ((bottom - top) & timestampMaskFromValidBits(36), 12u);
}

class TimingModes : public lbtest::GpuTest, public ::testing::WithParamInterface<const char*> {};

// Depth and frontend replays run the same LOD decision: every tessellation counter equals the
// shaded frame's; frontend discards before rasterization, so no fragment runs.
TEST_P(TimingModes, TessellationCountersAgreeAcrossModes) {
  Renderer r(gpu(), testTerrain(), {160, 90, 8});
  r.setScheme(*findScheme(GetParam()), {});
  auto pose = [](int f) { return lbtest::poseAt({-100, 300 - 20.0f * float(f), -100}, {500, 0, 500}); };
  auto shaded = replayInMode(r, RenderMode::Shaded, 3, 1, 1, pose);
  auto depth = replayInMode(r, RenderMode::Depth, 3, 1, 1, pose);
  auto frontend = replayInMode(r, RenderMode::Frontend, 3, 1, 1, pose);
  ASSERT_EQ(shaded.size(), 3u);
  EXPECT_EQ(compareTessellationCounters(shaded, depth, "depth"), "");
  EXPECT_EQ(compareTessellationCounters(shaded, frontend, "frontend"), "");
  for (size_t i = 0; i < shaded.size(); ++i) {
    EXPECT_GT(shaded[i].stats.tesInvocations, 0u);
    EXPECT_GT(shaded[i].stats.fsInvocations, 0u);
    EXPECT_EQ(frontend[i].stats.fsInvocations, 0u) << "frontend ran fragments";
    // Depth has no fragment shader; lavapipe still counts its depth-only fragments, as many as shaded
    // (same triangles, same depth test). Clipping sees the same triangles in both.
    EXPECT_EQ(depth[i].stats.fsInvocations, shaded[i].stats.fsInvocations);
    EXPECT_EQ(depth[i].stats.clipInvocations, shaded[i].stats.clipInvocations);
    EXPECT_GT(depth[i].gpuMs, 0.0);
    EXPECT_GT(frontend[i].gpuMs, 0.0);
  }
}
INSTANTIATE_TEST_SUITE_P(Schemes, TimingModes, ::testing::Values("uniform", "sphere"));

TEST(TimingModes, CounterMismatchIsNamed) {
  FrameResult a, b;
  a.frame = b.frame = 4;
  a.stats.tesInvocations = 10;
  b.stats.tesInvocations = 11;
  std::string msg = compareTessellationCounters({a}, {b}, "depth");
  EXPECT_NE(msg.find("frame 4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tes_invocations"), std::string::npos) << msg;
  EXPECT_NE(compareTessellationCounters({a}, {}, "depth"), "");
}

class Probe : public lbtest::GpuTest, public ::testing::WithParamInterface<std::tuple<RenderMode, bool>> {};
class ProbeInstanced : public lbtest::GpuTest {};

// The minimal loop runs, times positive, and does exactly the tessellation work of lodbench's
// uniform scheme at the same grid, level and camera; so does its vertex-height variant.
TEST_P(Probe, MatchesUniformSchemeWork) {
  const RenderMode mode = std::get<0>(GetParam());
  const int grid = 4, level = 5;
  auto pose = lbtest::overviewPose();
  ProbeOptions o;
  o.width = 96;
  o.height = 64;
  o.grid = grid;
  o.level = level;
  o.mode = mode;
  o.vertexHeight = std::get<1>(GetParam());
  o.warmup = 1;
  o.frames = 3;
  ProbeResult p = runProbe(gpu(), testTerrain(), pose, o);
  ASSERT_EQ(p.gpuMs.size(), 3u);
  EXPECT_GT(p.medianMs, 0.0);
  Renderer r(gpu(), testTerrain(), {96, 64, grid});
  r.setScheme(*findScheme("uniform"), {{"level", level}});
  auto same = [&](int) { return pose; };
  auto l = replayInMode(r, mode, 1, 1, 0, same);
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(p.stats.tcsPatches, l[0].stats.tcsPatches);
  EXPECT_EQ(p.stats.tesInvocations, l[0].stats.tesInvocations);
  EXPECT_EQ(p.stats.tesInvocations, uint64_t(grid * grid * (level + 1) * (level + 1)));
  if (mode == RenderMode::Frontend) {
    EXPECT_EQ(p.stats.fsInvocations, 0u);
  }
  if (mode == RenderMode::Shaded) {
    EXPECT_GT(p.stats.fsInvocations, 0u);
  }
}
// The instanced minimal loop draws the tessellated loop's triangles, and exactly the renderer's
// instanced path at the same grid, level and camera (counters and fragments).
TEST_F(ProbeInstanced, DrawsTheTessellatedLoopsTrianglesAndTheRenderersInstancedWork) {
  const int grid = 4, level = 6;
  auto pose = lbtest::overviewPose();
  ProbeOptions o;
  o.width = 96;
  o.height = 64;
  o.grid = grid;
  o.level = level;
  o.warmup = 1;
  o.frames = 3;
  ProbeResult tess = runProbe(gpu(), testTerrain(), pose, o);
  o.instanced = true;
  ProbeResult inst = runProbe(gpu(), testTerrain(), pose, o);
  EXPECT_GT(inst.medianMs, 0.0);
  EXPECT_EQ(inst.draws, 1u);
  EXPECT_EQ(inst.stats.tesInvocations, 0u);
  EXPECT_EQ(inst.stats.clipInvocations, tess.stats.clipInvocations);
  EXPECT_EQ(inst.stats.clipInvocations, uint64_t(grid * grid * level * level * 2));
  Renderer r(gpu(), testTerrain(), {96, 64, grid});
  r.setScheme(uniformInstancedScheme(), {{"level", level}, {"diagonal", 2}});
  auto same = [&](int) { return pose; };
  auto l = replayInMode(r, RenderMode::Shaded, 1, 1, 0, same);
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(inst.stats.clipInvocations, l[0].stats.clipInvocations);
  EXPECT_EQ(inst.stats.vsInvocations, l[0].stats.vsInvocations);
  EXPECT_EQ(inst.stats.fsInvocations, l[0].stats.fsInvocations);
}

INSTANTIATE_TEST_SUITE_P(Modes, Probe,
                         ::testing::Combine(::testing::Values(RenderMode::Shaded, RenderMode::Depth,
                                                              RenderMode::Frontend),
                                            ::testing::Bool()));

TEST(Calibration, StableNeedsThreeRunsWithinTolerance) {
  EXPECT_FALSE(calibrationStable({1.0, 1.0}, 0.01));
  EXPECT_TRUE(calibrationStable({2.0, 1.0, 1.005, 0.998}, 0.01));
  EXPECT_FALSE(calibrationStable({1.0, 1.0, 1.03}, 0.01));
}

TEST(Calibration, DriftOverLimitIsFlagged) {
  TimingSpec spec;
  CalibrationRun before{{1.0, 1.0, 1.0}, true};
  EXPECT_FALSE(calibrationJson(before, 1.015, spec)["flagged"].get<bool>());
  EXPECT_TRUE(calibrationJson(before, 1.03, spec)["flagged"].get<bool>());
  EXPECT_TRUE(calibrationJson(before, 0.97, spec)["flagged"].get<bool>());
  EXPECT_TRUE(calibrationJson(CalibrationRun{}, 1.0, spec)["flagged"].get<bool>());  // unknown is never "fine"
}

// A sweep with timing modes and calibration: each case records every mode's GPU time per frame and
// in its summary, the calibration figures, and a planted drift flags the case.
TEST(Calibration, SweepRecordsModesAndFlagsPlantedDrift) {
  const std::string dir = std::string(LODBENCH_SOURCE_DIR) + "/configs";
  Config c = parseConfig(R"({
    "name": "timing", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 1, "max_frames": 3,
    "terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
    "schemes": [{"name": "uniform", "params": {"level": 3}}],
    "timing": ["shaded", "depth", "frontend"], "calibration": {"level": 4, "frames": 2, "max_tries": 4, "min_load_s": 0.2}
  })",
                         "timing.json", dir);
  // A planted drift of 10x: lavapipe's own run-to-run noise (up to 1.5x here) can never cancel it.
  for (double drift : {0.0, 10.0}) {
    c.timing.testDrift = drift;
    fs::path out = fs::temp_directory_path() / ("lodbench_timing_" + std::to_string(int(drift * 10)));
    fs::remove_all(out);
    RunTotals t = runSweep(c, {out.string(), false, false});
    ASSERT_EQ(t.ok, 1);
    EXPECT_EQ(t.validationErrors, 0);
    fs::path caseFile = *fs::directory_iterator(out / "cases");
    std::ifstream in(caseFile);
    auto j = nlohmann::json::parse(in);
    const auto& s = j["summary"];
    for (const char* k : {"gpu_ms", "gpu_ms_depth", "gpu_ms_frontend", "cpu_harness_ms"})
      EXPECT_GT(s[k]["median"].get<double>(), 0.0) << k;
    ASSERT_EQ(j["frames"].size(), 3u);
    for (auto& f : j["frames"])
      for (const char* k : {"gpu_ms_depth", "gpu_ms_frontend", "cpu_harness_ms"}) EXPECT_TRUE(f.contains(k)) << k;
    const auto& cal = s["calibration"];
    EXPECT_GT(cal["before_ms"].get<double>(), 0.0);
    EXPECT_GT(cal["after_ms"].get<double>(), 0.0);
    EXPECT_GE(cal["load_s"].get<double>(), 0.2);  // sustained load before the counted runs
    EXPECT_GE(cal["before_runs"].size(), 1u);
    EXPECT_LE(cal["before_runs"].size(), 4u);
    EXPECT_EQ(cal["stable_before"].get<bool>(), calibrationStable(cal["before_runs"].get<std::vector<double>>(), 0.01));
    if (drift > 0) {
      EXPECT_TRUE(cal["flagged"].get<bool>()) << cal.dump();
    }
    fs::remove_all(out);
  }
}

// Bad timing/calibration config gives an InputError naming the field.
TEST(TimingConfig, BadKeysNameTheField) {
  const std::string dir = std::string(LODBENCH_SOURCE_DIR) + "/configs";
  auto parse = [&](const std::string& extra) {
    return parseConfig(R"({"name": "t", "terrain": {"type": "procedural", "size": 33}, "paths": ["paths/flyover.csv"],
      "schemes": ["uniform"], )" +
                           extra + "}",
                       "t.json", dir);
  };
  EXPECT_EQ(parse(R"("timing": ["shaded", "frontend"])").timing.modes,
            (std::vector<std::string>{"shaded", "frontend"}));
  EXPECT_TRUE(parse(R"("calibration": true)").timing.calibrate);
  EXPECT_EQ(parse(R"("calibration": {"level": 8})").timing.level, 8);
  for (const char* bad :
       {R"("timing": ["shaded", "wire"])", R"("timing": ["depth"])", R"("timing": ["shaded", "shaded"])",
        R"("calibration": {"levels": 8})", R"("calibration": {"max_tries": 2})"}) {
    try {
      parse(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      std::string msg = e.what();
      EXPECT_NE(msg.find("t.json:"), std::string::npos) << msg;
      EXPECT_TRUE(msg.find("/timing") != std::string::npos || msg.find("/calibration") != std::string::npos) << msg;
    }
  }
}

// Timings right by default: with no "calibration" in the config a GPU calibrates and a CPU
// rasterizer does not (its record says why); a GPU with "calibration": false is flagged in its
// record and the report says its clock was not controlled. A GPU is pretended on lavapipe with
// LODBENCH_TEST_DEVICE_TYPE=gpu.
TEST(Calibration, OnByDefaultOnAGpuAndAnUncontrolledClockIsFlagged) {
  const std::string dir = std::string(LODBENCH_SOURCE_DIR) + "/configs";
  auto config = [&](const std::string& calibration) {
    return parseConfig(R"({
      "name": "clock", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 1, "max_frames": 2,
      "terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
      "schemes": [{"name": "uniform", "params": {"level": 3}}])" +
                           calibration + "}",
                       "clock.json", dir);
  };
  EXPECT_FALSE(config("").timing.calibrateSet);
  EXPECT_TRUE(config(R"(, "calibration": false)").timing.calibrateSet);
  struct Case {
    bool gpu;
    std::string calibration;
    bool controlled, flagged;
  };
  for (const Case& k : {Case{false, "", false, false}, Case{true, "", true, false},
                        Case{true, R"(, "calibration": false)", false, true}}) {
    SCOPED_TRACE(std::string(k.gpu ? "gpu" : "cpu") + k.calibration);
    if (k.gpu) setenv("LODBENCH_TEST_DEVICE_TYPE", "gpu", 1);
    Config c = config(k.calibration);
    c.timing.minLoadS = 0.1;  // the default's sustained load, shortened for the test
    fs::path out = fs::temp_directory_path() / ("lodbench_clock_" + std::to_string(getpid()));
    fs::remove_all(out);
    RunTotals t = runSweep(c, {out.string(), false, false});
    unsetenv("LODBENCH_TEST_DEVICE_TYPE");
    ASSERT_EQ(t.ok, 1);
    const fs::path caseFile = fs::directory_iterator(out / "cases")->path();
    const auto j = nlohmann::json::parse(std::ifstream(caseFile));
    const auto& cal = j["summary"]["calibration"];
    EXPECT_EQ(cal["controlled"].get<bool>(), k.controlled) << cal.dump();
    if (!k.controlled) {  // a calibrated case's flag is its measured drift: lavapipe's noise decides it
      EXPECT_EQ(cal["flagged"].get<bool>(), k.flagged) << cal.dump();
      EXPECT_FALSE(cal["reason"].get<std::string>().empty());
    }
    ReportOptions ro;
    ro.runDir = out.string();
    ro.html = false;
    writeReport(ro);
    std::ifstream md(out / "report" / "report.md");
    const std::string page((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_EQ(page.find("Clock not controlled") != std::string::npos, k.flagged);
    fs::remove_all(out);
  }
}
