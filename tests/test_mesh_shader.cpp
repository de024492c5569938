// The mesh-shader path (render/mesh_drawer.cpp) against the schemes whose LOD it draws, on a device
// with VK_EXT_mesh_shader: every MeshShader test skips, with the reason, where the device lacks it
// (lavapipe, CI), and runs on a GPU through scripts/device-mesh-check.sh. On every frame of every
// shipped path, over a procedural terrain and the committed SRTM crop: sphere-ms draws exactly the
// triangles the pattern generator makes at the factors its task shader chose (read back through
// the factor capture), and sphere with integer partitioning draws as many at the same factors;
// cdlod-ms, cbt-ms and clusters-ms draw exactly their twins' triangles (clipper counts on every
// timed frame, histogram totals on every measured one); every mesh scheme has no crack site and no
// crack pixel, runs every render and timing mode, and the validation layer stays silent.
// MeshPath.* checks the skip itself on every device, by switching the feature off
// (LODBENCH_TEST_DISABLE).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli_run.h"
#include "config/config.h"
#include "dem_crop.h"
#include "gpu_fixture.h"
#include "schemes/preprocess/tess_patterns.h"
#include "shaders/shared.h"
#include "sweep/runner.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

constexpr int kFps = 5;  // every frame of each path sampled at 5 fps: 390 frames a terrain and scheme

class MeshShader : public lbtest::GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    if (!lbtest::gpu().meshShader)
      GTEST_SKIP() << lbtest::gpu().props.deviceName
                   << " lacks VK_EXT_mesh_shader (taskShader, meshShader): mesh-shader tests run on a GPU "
                      "(scripts/device-mesh-check.sh)";
  }
};

// The shipped paths as config entries, relative to configs/.
json shippedPaths() {
  json out = json::array();
  for (const std::string& name : lbtest::shippedPathFiles()) out.push_back("paths/" + name);
  return out;
}

json terrains() {
  const TerrainSpec dem = lbtest::demCrop();
  return {{{"type", "procedural"}, {"size", 257}, {"seed", 3}, {"extent", 1000}, {"height_scale", 150}},
          {{"type", "hgt"}, {"file", dem.file}, {"extent", dem.extent}, {"height_scale", dem.heightScale}}};
}

std::vector<Heightfield> terrainFields() {
  TerrainSpec procedural;
  procedural.size = 257;
  procedural.seed = 3;
  procedural.extent = 1000;
  procedural.heightScale = 150;
  std::vector<Heightfield> out;
  out.push_back(makeHeightfield(procedural));
  out.push_back(loadHeightfield(lbtest::demCrop()));
  return out;
}

// Triangles of a patch at captured factors (Renderer::capturedLevels), as the generator makes them.
uint64_t generatorTriangles(const float* levels, std::map<std::array<int, 6>, uint64_t>& memo) {
  std::array<int, 6> key;
  for (int k = 0; k < 6; ++k) key[size_t(k)] = int(levels[k]);
  if (std::min({key[0], key[1], key[2], key[3]}) == 0) return 0;  // culled
  auto it = memo.find(key);
  if (it != memo.end()) return it->second;
  const TessPattern p = tessellateQuad({{key[0], key[1], key[2], key[3]}, {key[4], key[5]}});
  uint64_t n = 0;
  for (const TessSubPatch& s : p.subPatches) n += s.triangles.size();
  return memo[key] = n;
}

}  // namespace

// sphere-ms's task shader makes sphere's decision; the factors it chose (captured as integers) give
// through the generator exactly the triangles the clipper and the histogram count. sphere with
// integer partitioning tessellates the same patches at the same factors into as many triangles.
TEST_F(MeshShader, SphereMsDrawsTheGeneratorsTrianglesAtTheFactorsItChose) {
  const Scheme& ms = *findScheme("sphere-ms");
  const Scheme& sphere = *findScheme("sphere");
  std::map<std::array<int, 6>, uint64_t> memo;
  int frames = 0;
  const std::vector<Heightfield> fields = terrainFields();
  for (size_t terrain = 0; terrain < fields.size(); ++terrain) {
    const Heightfield& hf = fields[terrain];
    const RenderSettings settings{320, 180, 16};
    Renderer r(lbtest::gpu(), hf, settings), twin(lbtest::gpu(), hf, settings);
    r.setScheme(ms, {});
    twin.setScheme(sphere, {{kIntegerParam, 1}});
    for (const std::string& file : lbtest::shippedPathFiles()) {
      const CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + file);
      for (int f = 0; f < frameCount(path, kFps); ++f) {
        SCOPED_TRACE("terrain " + std::to_string(terrain) + " " + file + " frame " + std::to_string(f));
        const CameraPose pose = samplePose(path, kFps, f, hf);
        FrameResult live, tess;
        r.renderImage(pose, pose, RenderMode::Shaded, &live);
        const std::vector<float> levels = r.capturedLevels();
        twin.renderImage(pose, pose, RenderMode::Shaded, &tess);
        const std::vector<float> tessLevels = twin.capturedLevels();
        ASSERT_EQ(levels.size(), size_t(r.patchCount()) * LB_CAPTURE_STRIDE);
        uint64_t expected = 0;
        int differing = 0;
        for (size_t p = 0; p < r.patchCount(); ++p) {
          const float* l = &levels[p * LB_CAPTURE_STRIDE];
          expected += generatorTriangles(l, memo);
          for (int k = 0; k < 6; ++k)
            differing += equalSpacingFactor(tessLevels[p * LB_CAPTURE_STRIDE + size_t(k)]) != int(l[k]) ? 1 : 0;
        }
        EXPECT_EQ(live.stats.clipInvocations, expected) << "the clipper's count";
        EXPECT_EQ(r.measureHistogram(pose, pose).total(), expected) << "the histogram's count";
        EXPECT_EQ(differing, 0) << "factors sphere.tesc chose, rounded as the tessellator rounds them";
        if (differing == 0) {
          EXPECT_EQ(tess.stats.clipInvocations, expected) << "sphere (integer) at the same factors";
        }
        // Mesh workgroups run exactly where triangles are drawn (a path leaving the terrain culls all).
        if (lbtest::gpu().meshShaderQueries) EXPECT_EQ(live.stats.meshInvocations > 0, expected > 0);
        ++frames;
      }
    }
  }
  EXPECT_GT(frames, 500);
}

// The twins through whole sweeps, as any case runs: every timed frame's triangles and instances
// equal the twin's, every measured frame's histogram total too; no crack site or pixel on any
// measured frame; images of every mode and the depth and front-end timing modes on the mesh path;
// no validation message.
TEST_F(MeshShader, TwinsDrawTheirTwinsTrianglesWithoutCracksInEveryMode) {
  const std::vector<std::pair<std::string, std::string>> twins = {
      {"cdlod", "cdlod-ms"}, {"cbt", "cbt-ms"}, {"clusters", "clusters-ms"}};
  // cbt at subd 5: a leaf's 1,024 triangles are more than a mesh workgroup emits, so cbt-ms cuts
  // each leaf into parts (shaders/cbt_meshlets.glsl); the default subd 3 sends whole leaves.
  const json subd5 = {{"subd", 5}};
  json schemes = json::array({"cdlod",
                              "cdlod-ms",
                              "cbt",
                              "cbt-ms",
                              {{"name", "cbt"}, {"params", subd5}},
                              {{"name", "cbt-ms"}, {"params", subd5}},
                              "sphere-ms",
                              "clusters",
                              "clusters-ms"});
  const json cfg = {{"name", "mesh-check"},
                    {"resolution", {320, 180}},
                    {"grid", 16},
                    {"fps", kFps},
                    {"warmup_frames", 2},
                    {"repetitions", 1},
                    {"terrains", terrains()},
                    {"paths", shippedPaths()},
                    {"schemes", schemes},
                    {"timing", {"shaded", "depth", "frontend"}},
                    {"calibration", false},  // counters are the point here, not clocks or energy
                    {"energy", false},
                    {"measure", {{"every", 1}, {"passes", {"histogram", "cracks"}}}},
                    {"images",
                     {{"frames", {0}},
                      {"modes", {"shaded", "heatmap", "wireframe", "error", "cracks"}},
                      {"resolution", {320, 180}},
                      {"worst", false}}}};
  const std::string configs = std::string(LODBENCH_SOURCE_DIR) + "/configs";
  Config c = parseConfig(cfg.dump(), "mesh-check.json", configs);
  const fs::path dir = fs::path(::testing::TempDir()) / ("lodbench_mesh_" + std::to_string(getpid()));
  fs::remove_all(dir);
  RunOptions o;
  o.outDir = dir.string();
  o.progress = false;
  o.validation = std::getenv("LODBENCH_VALIDATION") != nullptr;
  const RunTotals t = runSweep(c, o);
  EXPECT_EQ(t.failed, 0);
  EXPECT_EQ(t.skipped, 0);
  EXPECT_EQ(t.validationErrors, 0);
  std::map<std::string, json> cases;  // case id -> record
  for (const auto& e : fs::directory_iterator(dir / "cases")) {
    json j = json::parse(std::ifstream(e.path()));
    cases[j["case_id"].get<std::string>()] = j;
  }
  auto histTotal = [](const json& f) {
    uint64_t n = f["hist_offscreen"].get<uint64_t>() + f["hist_backfacing"].get<uint64_t>();
    for (const json& b : f["hist"]) n += b.get<uint64_t>();
    return n;
  };
  int compared = 0, measured = 0;
  for (const auto& [id, c] : cases) {
    ASSERT_EQ(c["status"], "ok") << id << ": " << c["reason"];
    const std::string scheme = c["scheme"];
    if (scheme.size() > 3 && scheme.substr(scheme.size() - 3) == "-ms")
      for (const json& f : c["frames"]) {
        if (!f.contains("cracks_analytic")) continue;
        EXPECT_EQ(f["cracks_analytic"], 0) << id << " frame " << f["frame"];
        EXPECT_EQ(f["cracks_pixels"], 0) << id << " frame " << f["frame"];
        ++measured;
      }
    for (const auto& [base, ms] : twins) {
      if (scheme != base) continue;
      const std::string other = ms + id.substr(base.size());
      ASSERT_TRUE(cases.count(other)) << other;
      const json &a = c["frames"], &b = cases[other]["frames"];
      ASSERT_EQ(a.size(), b.size()) << id;
      for (size_t i = 0; i < a.size(); ++i) {
        SCOPED_TRACE(other + " frame " + a[i]["frame"].dump());
        EXPECT_EQ(a[i]["clip_invocations"], b[i]["clip_invocations"]);
        EXPECT_EQ(a[i]["instances"], b[i]["instances"]);
        if (a[i].contains("hist") && b[i].contains("hist")) {
          EXPECT_EQ(histTotal(a[i]), histTotal(b[i]));
        }
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(measured, 1000);
  std::printf("[MeshShader] %zu cases, %d twin frames compared, %d mesh frames checked for cracks\n", cases.size(),
              compared, measured);
  fs::remove_all(dir);
}

// Where the device has no mesh shaders, a mesh scheme's case is skipped with the reason and the
// run goes on (exit 0); the feature is switched off here, so every device shows it.
TEST(MeshPath, SkippedWithTheReasonWhereTheDeviceLacksMeshShaders) {
  const std::string dir = ::testing::TempDir() + "/lodbench_mesh_skip_" + std::to_string(getpid());
  fs::remove_all(dir);
  const json cfg = {{"name", "mesh-skip"},
                    {"resolution", {64, 36}},
                    {"grid", 4},
                    {"fps", 30},
                    {"warmup_frames", 0},
                    {"max_frames", 2},
                    {"terrain", {{"type", "procedural"}, {"size", 65}, {"seed", 1}, {"extent", 1000}}},
                    {"paths", {std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv"}},
                    {"schemes", {"sphere-ms", "cdlod-ms", "cbt-ms"}},
                    {"measure", {{"every", 0}}}};
  fs::create_directories(dir);
  std::ofstream(dir + "/skip.json") << cfg.dump();
  const lb::test::CliOut out = lb::test::shell("env LODBENCH_TEST_DISABLE=meshShader " + std::string(LODBENCH_BINARY) +
                                               " run " + dir + "/skip.json --out " + dir + "/run -q");
  EXPECT_EQ(out.code, 0) << out.text;
  int skipped = 0;
  for (const auto& e : fs::directory_iterator(dir + "/run/cases")) {
    const json c = lb::test::readJson(e.path().string());
    EXPECT_EQ(c["status"], "skipped") << e.path();
    EXPECT_NE(c["reason"].get<std::string>().find("lacks VK_EXT_mesh_shader"), std::string::npos) << c["reason"];
    ++skipped;
  }
  EXPECT_EQ(skipped, 3);
  fs::remove_all(dir);
}
