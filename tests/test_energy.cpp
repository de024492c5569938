// Energy per frame: the board's energy counter (NVML on NVIDIA, loaded at run
// time) over windows of whole ticks, the path looped until the window is long enough, 3 rounds
// with their spread; null with its reason where there is no counter. A stand-in counter that ticks
// at a known period and power gives the right joules per frame.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "config/case_identity.h"
#include "config/config.h"
#include "error.h"
#include "gpu_fixture.h"
#include "render/lod_state.h"
#include "replay/energy_pass.h"
#include "replay/lod_replay.h"
#include "report/equal_error.h"
#include "report/report.h"
#include "report/run_data.h"
#include "sweep/runner.h"
#include "vk/device_identity.h"
#include "vk/energy_counter.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A load on a virtual clock: each frame takes exactly dt seconds of the counter's clock.
struct VirtualLoad {
  double t = 0, dt;
  int64_t frames = 0;
  explicit VirtualLoad(double frameS) : dt(frameS) {}
  std::function<double()> clock() {
    return [this] { return t; };
  }
  std::function<int64_t()> draw() {
    return [this] {
      t += dt;
      return ++frames;
    };
  }
};

CameraPose poseOf(int f) {
  return lbtest::poseAt({-100, 300 - 20.0f * float(f), -100}, {500, 0, 500});
}

}  // namespace

// 50 W, a frame every 1 ms: 0.05 J a frame; ticks of 10 ms; windows of at least 50 ms, 3 rounds.
TEST(Energy, StandInCounterGivesTheKnownJoulesPerFrame) {
  for (double frameMs : {1.0, 0.7, 3.3}) {
    SCOPED_TRACE(frameMs);
    VirtualLoad load(frameMs / 1000);
    StandInEnergyCounter counter(0.010, 50.0, load.clock());
    EnergyResult r = measureEnergy(counter, 0.050, 3, load.draw());
    ASSERT_TRUE(r.measured()) << r.reason;
    ASSERT_EQ(r.rounds.size(), 3u);
    const double known = 50.0 * frameMs / 1000;
    for (const EnergyRound& k : r.rounds) {
      EXPECT_GE(k.seconds, 0.050) << "the window is at least window_s";
      EXPECT_LT(k.seconds, 0.050 + 0.010 + frameMs / 1000) << "and closes at the first tick after it";
      EXPECT_GT(k.frames, 0);
      // Within the tick quantisation: the window's ends are seen at most a frame after their tick.
      EXPECT_NEAR(k.jPerFrame(), known, known * 2.0 / double(k.frames)) << k.joules << " J / " << k.frames;
      EXPECT_NEAR(k.tickMs, 10.0, frameMs + 1e-9) << "the tick measured";
      // The counter moved by whole ticks of 0.5 J.
      EXPECT_NEAR(std::fmod(k.joules + 1e-9, 0.5), 0.0, 1e-6) << k.joules;
    }
    if (frameMs == 1.0)  // tick-aligned frames: exact
      for (const EnergyRound& k : r.rounds) EXPECT_DOUBLE_EQ(k.jPerFrame(), 0.05);
  }
}

// Three rounds: the mean, their range and the spread (max - min) / mean are recorded; unknown is
// null with its reason, never 0.
TEST(Energy, JsonRecordsRoundsAndSpreadOrNullWithAReason) {
  EnergyResult r;
  r.windowS = 2;
  r.pathFrames = 10;
  r.counter = "stand-in";
  for (double j : {1.0, 1.1, 0.9}) {
    EnergyRound k;
    k.frames = 100;
    k.joules = j * 100;
    k.seconds = 2.05;
    k.tickMs = 100;
    r.rounds.push_back(k);
  }
  json j = energyJson(r);
  ASSERT_TRUE(j["energy_j_per_frame"].is_object()) << j.dump();
  EXPECT_TRUE(j["energy_reason"].is_null());
  const json& e = j["energy_j_per_frame"];
  EXPECT_NEAR(e["mean"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(e["spread"].get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(e["min"].get<double>(), 0.9, 1e-12);
  EXPECT_NEAR(e["max"].get<double>(), 1.1, 1e-12);
  EXPECT_EQ(e["rounds"].size(), 3u);
  EXPECT_EQ(e["path_passes"][0], 10.0);
  EXPECT_EQ(e["tick_ms"], 100.0);
  EXPECT_EQ(e["counter"], "stand-in");
  EXPECT_TRUE(e["sm_clock_mhz"][0].is_null());

  EnergyResult none;
  none.reason = "not an NVIDIA device";
  json n = energyJson(none);
  EXPECT_TRUE(n["energy_j_per_frame"].is_null());
  EXPECT_EQ(n["energy_reason"], "not an NVIDIA device");
}

// Counters that cannot give a figure say why: another vendor, no NVML library, a stuck counter.
TEST(Energy, NoCounterGivesAReasonNotAFigure) {
  NvmlEnergyCounter other(0x10005, "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f");
  EXPECT_FALSE(other.available());
  EXPECT_EQ(other.reason(), "not an NVIDIA device (vendor 0x10005): NVML reads NVIDIA boards only");
  EXPECT_NE(other.clocks().reason.find("not an NVIDIA device"), std::string::npos);
  EXPECT_LT(other.clocks().smMhz, 0);
  NvmlEnergyCounter noLib(kNvidiaVendorId, "6c3b5f2e-0d1a-4b6e-9f10-2a3b4c5d6e7f", "libnvidia-ml-absent.so.1");
  EXPECT_EQ(noLib.reason().rfind("NVML not available (", 0), 0u) << noLib.reason();
  VirtualLoad load(0.001);
  EnergyResult r = measureEnergy(noLib, 2, 3, load.draw());
  EXPECT_FALSE(r.measured());
  EXPECT_EQ(r.reason, noLib.reason());
  EXPECT_EQ(load.frames, 0) << "nothing drawn without a counter";
  // A counter that never moves: 0 W.
  StandInEnergyCounter stuck(0.010, 0.0, load.clock());
  EnergyResult s = measureEnergy(stuck, 0.05, 3, load.draw());
  EXPECT_FALSE(s.measured());
  EXPECT_NE(s.reason.find("did not change"), std::string::npos) << s.reason;
  // The tick measured on a real clock.
  StandInEnergyCounter ticking(0.004, 10.0);
  EXPECT_NEAR(measureTickMs(ticking, 1.0), 4.0, 3.0);
  EXPECT_LT(measureTickMs(noLib, 0.1), 0);
}

class EnergyPass : public lbtest::GpuTest {};

// On the renderer with the stand-in on the real clock: a 3-frame path is far shorter than the
// window, so the pass loops it; J/frame = watts x the window's seconds / its frames within one
// tick's quantisation; every window lasts at least window_s.
TEST_F(EnergyPass, LoopsThePathUntilTheWindowIsLongEnough) {
  Renderer r(gpu(), testTerrain(), {160, 90, 4});
  r.setScheme(*findScheme("uniform"), {{"level", 3}});
  TimingSpec spec;
  spec.energyWindowS = 0.25;  // several path loops even where frames are slow (sanitizers, a loaded machine)
  spec.energyRounds = 3;
  const double watts = 20, tickS = 0.010;
  StandInEnergyCounter counter(tickS, watts);
  EnergyResult e = energyPass(r, counter, spec, 3, poseOf, [] {});
  ASSERT_TRUE(e.measured()) << e.reason;
  ASSERT_EQ(e.rounds.size(), 3u);
  EXPECT_EQ(e.pathFrames, 3);
  for (const EnergyRound& k : e.rounds) {
    EXPECT_GE(k.seconds, 0.25);
    EXPECT_GT(k.frames, 3) << "the path looped";
    const double known = watts * k.seconds / double(k.frames);
    // Within the tick quantisation (a window's ends are seen a frame or so after their ticks).
    EXPECT_NEAR(k.jPerFrame(), known, watts * 2 * tickS / double(k.frames)) << k.frames << " frames";
  }
  json j = energyJson(e);
  EXPECT_GT(j["energy_j_per_frame"]["path_passes"][0].get<double>(), 1.0);
  EXPECT_TRUE(j["energy_j_per_frame"]["spread"].is_number());
  // "energy": false: no figure, the reason says so, nothing drawn.
  spec.energy = false;
  EnergyResult off = energyPass(r, counter, spec, 3, poseOf, [] {});
  EXPECT_FALSE(off.measured());
  EXPECT_EQ(off.reason, "\"energy\": false in the config");
}

// A stateful scheme (cbt) restores its converged snapshot at the start of every pass over the
// path, as the timed passes do; the pass runs clean under the validation layer.
TEST_F(EnergyPass, StatefulSchemeRestoresItsSnapshotEachLoop) {
  Renderer r(gpu(), testTerrain(), {96, 54, 4});
  r.setScheme(*findScheme("cbt"), {});
  ASSERT_TRUE(r.statefulLod());
  convergeLod(r, poseOf(0));
  r.lodState().snapshot();
  const std::vector<uint32_t> snapshot = r.lodState().read();
  TimingSpec spec;
  spec.energyWindowS = 0.03;
  spec.energyRounds = 2;
  StandInEnergyCounter counter(0.005, 10);
  EnergyResult e = energyPass(r, counter, spec, 2, poseOf, [] {});
  ASSERT_TRUE(e.measured()) << e.reason;
  for (const EnergyRound& k : e.rounds) EXPECT_GT(k.frames, 2);
  // Restoring gives back the snapshot the timed passes start from.
  r.lodState().restore();
  EXPECT_EQ(r.lodState().read(), snapshot);
}

// Lowest first; "<" only where the rounds are apart, "≈" (not ranked) where they overlap, and the
// equal-error section says so beside a J/frame column.
TEST(Energy, RankedOnlyBeyondTheSensorsSpread) {
  EXPECT_EQ(energyRanking({{"b", 2.0, 1.9, 2.1, 0.1}, {"a", 1.0, 0.95, 1.05, 0.1}}),
            "a 1 J (spread 10.0%) < b 2 J (spread 10.0%)");
  EXPECT_EQ(energyRanking({{"a", 1.0, 0.9, 1.1, 0.2}, {"b", 1.05, 1.0, 1.1, 0.1}}),
            "a 1 J (spread 20.0%) ≈ b 1.05 J (spread 10.0%)");
  // c overlaps a though b does not: a chain never ranks c above a.
  EXPECT_EQ(energyRanking({{"a", 1.0, 0.99, 1.01, 0.02}, {"b", 1.1, 1.09, 1.11, 0.02}, {"c", 1.2, 0.5, 1.9, 1.2}}),
            "a 1 J (spread 2.0%) ≈ b 1.1 J (spread 2.0%) ≈ c 1.2 J (spread 120.0%)");

  ReportRun run;
  run.context = {{"device", "NVIDIA H100 80GB HBM3"}};
  auto add = [&](const std::string& scheme, json energy) {
    ReportCase c;
    c.id = scheme;
    c.scheme = scheme;
    c.status = "ok";
    c.matched = {{"metric", "err_p95_px"}, {"target", 1.0}, {"param", "p"}, {"value", 1}, {"achieved", 1.0}};
    c.summary = {{"gpu_ms", {{"median", 1.0}, {"p95", 1.2}}}};
    if (energy.is_object())
      c.summary["energy_j_per_frame"] = energy, c.summary["energy_reason"] = nullptr;
    else
      c.summary["energy_j_per_frame"] = nullptr, c.summary["energy_reason"] = energy;
    run.cases.push_back(c);
  };
  add("sphere", {{"mean", 0.020}, {"min", 0.019}, {"max", 0.021}, {"spread", 0.1}});
  add("cdlod", {{"mean", 0.010}, {"min", 0.0098}, {"max", 0.0102}, {"spread", 0.04}});
  add("cbt", {{"mean", 0.0205}, {"min", 0.0200}, {"max", 0.0210}, {"spread", 0.05}});
  add("uniform", "NVML total energy counter: Not Supported");
  const EqualErrorSection eq = equalErrorSection(run);
  ASSERT_TRUE(eq.present);
  const auto& h = eq.table.header;
  const size_t col = size_t(std::find(h.begin(), h.end(), "energy J/frame") - h.begin());
  ASSERT_LT(col, h.size());
  EXPECT_EQ(h[col - 1], "GPU ms p95") << "beside the milliseconds";
  EXPECT_EQ(h[col + 1], "energy spread");
  for (const auto& row : eq.table.rows) {
    if (row[0].md == "uniform") EXPECT_EQ(row[col].md, "–");
    if (row[0].md == "cdlod") EXPECT_EQ(row[col].md, "0.01");
  }
  EXPECT_NE(eq.energy.find("cdlod 0.01 J (spread 4.0%) < sphere 0.02 J (spread 10.0%) ≈ cbt 0.0205 J"),
            std::string::npos)
      << eq.energy;
  EXPECT_NE(eq.energy.find("within the sensor's spread"), std::string::npos) << eq.energy;
  EXPECT_NE(eq.energy.find("uniform (NVML total energy counter: Not Supported)"), std::string::npos) << eq.energy;
}

// Config: "energy": false, or {"window_s", "rounds"}; bad keys named; the digest changes only when
// the setting is not the default (earlier sweeps' digests still match).
TEST(Energy, ConfigAndDigest) {
  const std::string dir = std::string(LODBENCH_SOURCE_DIR) + "/configs";
  auto parse = [&](const std::string& extra) {
    return parseConfig(R"({"name": "t", "terrain": {"type": "procedural", "size": 33}, "paths": ["paths/flyover.csv"],
      "schemes": ["uniform"])" +
                           extra + "}",
                       "t.json", dir);
  };
  const Config d = parse("");
  EXPECT_TRUE(d.timing.energy);
  EXPECT_EQ(d.timing.energyWindowS, 2.0);
  EXPECT_EQ(d.timing.energyRounds, 3);
  EXPECT_FALSE(parse(R"(, "energy": false)").timing.energy);
  const Config c = parse(R"(, "energy": {"window_s": 0.5, "rounds": 5})");
  EXPECT_EQ(c.timing.energyWindowS, 0.5);
  EXPECT_EQ(c.timing.energyRounds, 5);
  EXPECT_FALSE(measurementInputs(d).at("timing").contains("energy"));
  EXPECT_EQ(measurementInputs(c)["timing"]["energy"]["rounds"], 5);
  EXPECT_EQ(measurementInputs(parse(R"(, "energy": false)"))["timing"]["energy"], false);
  for (const char* bad : {R"(, "energy": {"window": 2})", R"(, "energy": {"rounds": 0})", R"(, "energy": "on")"}) {
    try {
      parse(bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("/energy"), std::string::npos) << e.what();
    }
  }
}

// A real run: on lavapipe (no counter) the case is ok, energy null with its reason in the summary,
// the context's tick and clocks null with theirs; with the stand-in (LODBENCH_TEST_ENERGY_COUNTER)
// every case records 3 rounds, their spread and the tick, and the report's case table has the
// J/frame column.
TEST(Energy, RunRecordsEnergyOrWhyNot) {
  const std::string dir = std::string(LODBENCH_SOURCE_DIR) + "/configs";
  Config c = parseConfig(R"({
    "name": "energy", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 1, "max_frames": 2,
    "terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
    "schemes": [{"name": "uniform", "params": {"level": 3}}, {"name": "sphere"}],
    "measure": {"every": 0}, "energy": {"window_s": 0.05, "rounds": 3}
  })",
                         "energy.json", dir);
  for (bool standIn : {false, true}) {
    SCOPED_TRACE(standIn ? "stand-in" : "this device");
    if (standIn) setenv("LODBENCH_TEST_ENERGY_COUNTER", "5:20", 1);
    fs::path out = fs::temp_directory_path() / ("lodbench_energy_" + std::to_string(getpid()));
    fs::remove_all(out);
    RunTotals t = runSweep(c, {out.string(), false, false});
    unsetenv("LODBENCH_TEST_ENERGY_COUNTER");
    ASSERT_EQ(t.ok, 2);
    const json ctx = json::parse(std::ifstream(out / "run.json"))["context"];
    for (const char* k : {"energy_tick_ms", "energy_reason", "energy_counter", "sm_clock_mhz", "sm_clock_max_mhz",
                          "mem_clock_mhz", "mem_clock_max_mhz", "clocks_reason"})
      EXPECT_TRUE(ctx.contains(k)) << k;
    for (const auto& f : fs::directory_iterator(out / "cases")) {
      const json s = json::parse(std::ifstream(f.path()))["summary"];
      ASSERT_TRUE(s.contains("energy_j_per_frame")) << f.path();
      if (!standIn && ctx["vendor_id"] != kNvidiaVendorId) {
        EXPECT_TRUE(s["energy_j_per_frame"].is_null());
        EXPECT_NE(s["energy_reason"].get<std::string>().find("not an NVIDIA device"), std::string::npos);
        EXPECT_TRUE(ctx["energy_tick_ms"].is_null());
        EXPECT_TRUE(ctx["sm_clock_mhz"].is_null());
        EXPECT_FALSE(ctx["clocks_reason"].get<std::string>().empty());
        EXPECT_FALSE(ctx["energy_reason"].get<std::string>().empty());
      } else if (standIn) {
        const json& e = s["energy_j_per_frame"];
        ASSERT_TRUE(e.is_object()) << s["energy_reason"];
        EXPECT_EQ(e["rounds"].size(), 3u);
        EXPECT_TRUE(e["spread"].is_number());
        EXPECT_GT(e["mean"].get<double>(), 0.0);
        for (auto& sec : e["round_seconds"]) EXPECT_GE(sec.get<double>(), 0.05);
        EXPECT_EQ(e["counter"], "stand-in");
        EXPECT_NEAR(ctx["energy_tick_ms"].get<double>(), 5.0, 2.0);
      }
    }
    ReportOptions ro;
    ro.runDir = out.string();
    ro.html = false;
    writeReport(ro);
    std::ifstream md(out / "report" / "report.md");
    const std::string page((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_EQ(page.find("energy J/frame") != std::string::npos, standIn);
    fs::remove_all(out);
  }
}
