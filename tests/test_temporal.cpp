// Temporal stability: popping at lags 1, 2 and 3 (replay/popping.h) on a planted LOD that alternates
// between two states every frame and on a static one, and the lag of a LOD behind the camera
// (replay/settle.h) on a planted error series and on cbt after the fast dive.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "gpu_fixture.h"
#include "replay/measure.h"
#include "replay/settle.h"
#include "sweep/runner.h"
#include "sweep_run.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 160, kH = 90, kGrid = 8;

// Low over the terrain looking down, and high above the far corner: sphere's levels near the low
// camera differ by an order of magnitude between the two.
CameraPose nearPose() {
  return lbtest::poseAt({500, 300, 400}, {500, 0, 520});
}
CameraPose farPose() {
  return lbtest::poseAt({-1500, 2500, -1500}, {-3000, 0, -3000});
}

double value(const FrameMetrics& m, const std::string& key) {
  for (auto& [k, v] : m.values)
    if (k == key) return v;
  ADD_FAILURE() << key << " missing";
  return std::nan("");
}

// Frame t of a path whose LOD camera alternates between two poses every frame (a LOD that flips
// between two states), measured with its LOD cameras of frames t-1 .. t-3.
FrameMetrics measureAt(int frame, const std::function<CameraPose(int)>& pose) {
  Renderer r(gpu(), testTerrain(), {kW, kH, kGrid});
  r.setScheme(*findScheme("sphere"), {});
  MeasureSpec spec;
  spec.every = 1;
  spec.passes = {"popping"};
  ReferenceCache refs;
  OlderLod older;
  for (int k = 2; k <= kPopLags && frame - k >= 0; ++k) older.poses.push_back(pose(frame - k));
  return measureFrame(gpu(), r, *findScheme("sphere"), r.params(), testTerrain(), "t", spec, refs, frame,
                      pose(frame - 1), pose(frame), nullptr, false, &older);
}

}  // namespace

class Temporal : public lbtest::GpuTest {};

TEST_F(Temporal, AlternatingLodPopsAtOddLagsOnly) {
  auto alternating = [](int f) { return f % 2 == 0 ? nearPose() : farPose(); };
  FrameMetrics m = measureAt(4, alternating);  // near; lags 1 and 3 far, lag 2 near
  EXPECT_GT(value(m, "pop_mean"), 0.1);
  EXPECT_GT(value(m, "pop3_mean"), 0.1);
  EXPECT_GT(value(m, "pop_changed"), 0.05 * kW * kH);
  EXPECT_EQ(value(m, "pop2_mean"), 0.0);
  EXPECT_EQ(value(m, "pop2_changed"), 0.0);
  EXPECT_EQ(value(m, "pop_mean"), value(m, "pop3_mean"));  // the same two states
  // Frame 2 has no frame t - 3: null, not 0.
  FrameMetrics early = measureAt(2, alternating);
  EXPECT_TRUE(std::isnan(value(early, "pop3_mean")));
  EXPECT_TRUE(std::isnan(value(early, "pop3_changed")));
  EXPECT_EQ(value(early, "pop2_mean"), 0.0);
}

TEST_F(Temporal, StaticLodOnAStaticCameraIsZeroAtEveryLag) {
  FrameMetrics m = measureAt(3, [](int) { return nearPose(); });
  for (const char* k : {"pop_mean", "pop2_mean", "pop3_mean", "pop_changed", "pop2_changed", "pop3_changed"})
    EXPECT_EQ(value(m, k), 0.0) << k;
}

TEST(Settle, PlantedLagIsCountedWithItsFrames) {
  // Settled error 1 px everywhere; a jump at frame 5 leaves the LOD 8x off, halving its excess every
  // frame: 8, 4.5, 2.75, 1.875, 1.44, 1.22, 1.11, 1.05 ... (within 10 % from frame 12 on: 1.055).
  std::vector<SettleFrame> s;
  for (int f = 0; f < 20; ++f) s.push_back({f, f < 5 ? 1.0 : 1.0 + 7.0 / std::pow(2.0, f - 5), 1.0});
  json j = settleJson(s, "updates");
  EXPECT_EQ(j["frames"], 7);  // frames 5 .. 11
  EXPECT_EQ(j["from"], 5);
  EXPECT_EQ(j["to"], 11);
  EXPECT_EQ(j["off_frames"], 7);
  ASSERT_EQ(j["counted"].size(), 8u);  // the run and the first frame back within the tolerance
  EXPECT_EQ(j["counted"][7]["frame"], 12);
  // A second, shorter lag and a frame without terrain: the longest run is reported, the unknown
  // frame ends a run and is not compared.
  s[15].err = 1.5;
  s[16].err = std::nan("");
  j = settleJson(s, "updates");
  EXPECT_EQ(j["frames"], 7);
  EXPECT_EQ(j["off_frames"], 8);
  EXPECT_EQ(j["frames_compared"], 19);
  // A LOD of the camera alone is settled on every frame.
  EXPECT_EQ(settledByCamera(20)["frames"], 0);
}

// Through whole sweeps: cbt (a stateful tree) and sphere on a camera that does not move pop at no
// lag and never lag; cbt after the fast dive reports its lag with the frames it counted.
TEST(Settle, CbtAfterTheFastDiveAndOnAStaticCamera) {
  const fs::path staticPath = fs::path(::testing::TempDir()) / ("lodbench_static_" + std::to_string(getpid()) + ".csv");
  std::ofstream(staticPath) << "time,eye_x,eye_y,eye_z,target_x,target_y,target_z,fov\n"
                               "0,0.3,0.25,0.3,0.6,0.0,0.6,60\n1,0.3,0.25,0.3,0.6,0.0,0.6,60\n";
  json cfg = {
      {"name", "temporal"},
      {"resolution", {kW, kH}},
      {"grid", 16},
      {"fps", 30},
      {"warmup_frames", 2},
      {"max_frames", 24},
      {"terrain", {{"type", "procedural"}, {"size", 257}, {"seed", 1}, {"extent", 1000}, {"height_scale", 120}}},
      {"paths", {"paths/dive.csv", staticPath.string()}},
      {"schemes", {"cbt", "sphere"}},
      {"measure", {{"every", 3}, {"passes", {"error", "popping"}}}}};
  const fs::path dir = lbtest::runConfig(cfg, "temporal_dive");
  int cases = 0;
  for (const auto& e : fs::directory_iterator(dir / "cases")) {
    json c = json::parse(std::ifstream(e.path()));
    const std::string id = c["case_id"];
    const json& s = c["summary"];
    const json& settle = s["settle"];
    ASSERT_TRUE(settle.is_object()) << id;
    EXPECT_EQ(settle["settled_by"], c["scheme"] == "cbt" ? "updates" : "camera") << id;
    if (id.find("_dive_") != std::string::npos && c["scheme"] == "cbt") {
      // The run it counted: consecutive frames, each off its settled error by more than 10 %, then
      // the frame back within it.
      const json& counted = settle["counted"];
      const int n = settle["frames"];
      std::printf("cbt after the fast dive: %d frame(s) off their settled error, from %s to %s: %s\n", n,
                  settle["from"].dump().c_str(), settle["to"].dump().c_str(), counted.dump().c_str());
      ASSERT_EQ(counted.size(), size_t(n == 0 ? 0 : n + 1)) << id;
      for (int i = 0; i < int(counted.size()); ++i) {
        const double err = counted[i]["err_mean_px"], settled = counted[i]["settled_err_mean_px"];
        EXPECT_EQ(counted[i]["frame"], settle["from"].get<int>() + i);
        if (i < n)
          EXPECT_GT(std::abs(err - settled), 0.1 * settled) << id << " frame " << counted[i]["frame"];
        else
          EXPECT_LE(std::abs(err - settled), 0.1 * settled) << id;
      }
    }
    if (id.find("lodbench_static") != std::string::npos) {
      EXPECT_EQ(settle["frames"], 0) << id;
      for (const char* k : {"pop_mean", "pop2_mean", "pop3_mean"}) EXPECT_EQ(s[k]["max"], 0.0) << id << " " << k;
    }
    ++cases;
  }
  EXPECT_EQ(cases, 4);
  fs::remove(staticPath);
}
