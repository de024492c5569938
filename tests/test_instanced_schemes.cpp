// The instanced-grid schemes measured like every other scheme, through whole sweeps: crack-free by
// construction on every shipped path and scenario (drawn-mesh check and image holes), with negative
// controls that crack; cdlod-sse within its error bound; morphing pops less than not morphing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "dem_crop.h"
#include "gpu_fixture.h"
#include "metrics/mesh_cracks.h"
#include "render/scheme.h"
#include "schemes/registry.h"
#include "sweep/runner.h"
#include "sweep_run.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";

std::vector<std::string> instancedSchemes() {
  std::vector<std::string> out;
  for (const Scheme* s : lbtest::drawableSchemes())
    if (s->info().path != DrawPath::Tessellation) out.push_back(s->info().name);  // cbt, and mesh twins on GPUs
  return out;
}

json schemeList(const std::vector<std::string>& names) {
  json a = json::array();
  for (auto& n : names) a.push_back({{"name", n}});
  return a;
}

std::vector<std::string> shippedPaths() {
  std::vector<std::string> out;
  for (const std::string& name : lbtest::shippedPathFiles()) out.push_back("paths/" + name);
  return out;
}

json smallRun(const std::string& name, json paths, json schemes, json measure) {
  return {{"name", name},
          {"resolution", {160, 90}},
          {"grid", 16},
          {"fps", 4},
          {"warmup_frames", 0},
          {"repetitions", 1},
          {"terrain", {{"type", "procedural"}, {"size", 257}, {"seed", 3}, {"extent", 1000}, {"height_scale", 150}}},
          {"paths", paths},
          {"schemes", schemes},
          {"measure", measure}};
}

}  // namespace

// Every other frame measured at 1 fps: a pose every 2 s of every shipped path (over 300 measured
// frames on lavapipe). The ASan pass runs this test, and it was its longest (113 s measuring every
// frame); InstancedSchemes.NoCracksInEveryScenario covers the scenarios' own paths and terrains.
TEST(InstancedSchemes, NoCracksAndNoSeamRiskOnEveryShippedPath) {
  ASSERT_GE(instancedSchemes().size(), 2u);
  json cfg = smallRun("instanced-cracks", shippedPaths(), schemeList(instancedSchemes()),
                      {{"every", 2}, {"passes", {"cracks"}}});
  cfg["fps"] = 1;
  int frames = 0;
  for (const json& c : lbtest::sweepCases(cfg, "instanced_paths")) {
    const std::string id = c["case_id"];
    ASSERT_EQ(c["status"], "ok") << id << ": " << c["reason"];
    for (auto [f, v] : lbtest::perFrame(c, "cracks_analytic")) EXPECT_EQ(v, 0) << id << " frame " << f;
    for (auto [f, v] : lbtest::perFrame(c, "cracks_pixels")) EXPECT_EQ(v, 0) << id << " frame " << f;
    for (auto [f, v] : lbtest::perFrame(c, "cdlod_seam_risk")) EXPECT_EQ(v, 0) << id << " frame " << f;
    frames += int(lbtest::perFrame(c, "cracks_analytic").size());
  }
  EXPECT_GT(frames, 100);
}

// Each scenario's own terrains, paths, resolution and measured frames, with the instanced schemes.
TEST(InstancedSchemes, NoCracksInEveryScenario) {
  int scenarios = 0;
  for (const auto& e : fs::directory_iterator(kConfigs + "/scenarios")) {
    if (e.path().extension() != ".json") continue;
    json cfg = json::parse(std::ifstream(e.path()));
    cfg["schemes"] = schemeList(instancedSchemes());
    cfg["measure"] = {{"every", cfg["measure"].value("every", 8)}, {"passes", {"cracks"}}};
    cfg.erase("images");
    cfg.erase("match");
    const std::string tag = e.path().stem().string();
    for (const json& c : lbtest::sweepCases(cfg, "instanced_" + tag, kConfigs + "/scenarios")) {
      const std::string id = c["case_id"];
      // The far-origin scenario's third terrain sits 10,000 km out, where float positions are 1 m
      // apart: it exists to show every scheme breaking there (tessellated ones included), and the
      // morph's distances break with them. 100 km is asserted like the origin.
      if (tag == "far-origin" && id.find("at10000000") != std::string::npos) continue;
      ASSERT_EQ(c["status"], "ok") << tag << " " << id << ": " << c["reason"];
      for (auto [f, v] : lbtest::perFrame(c, "cracks_analytic")) EXPECT_EQ(v, 0) << tag << " " << id << " frame " << f;
      for (auto [f, v] : lbtest::perFrame(c, "cracks_pixels")) EXPECT_EQ(v, 0) << tag << " " << id << " frame " << f;
    }
    ++scenarios;
  }
  EXPECT_GE(scenarios, 8);
}

// Negative controls: without the morph, cdlod's and cdlod-sse's level changes leave T-junctions
// that the drawn-mesh check sees. And the morph exists to stop popping: cdlod's worst frame pops at
// most half as much with it. Its mean over frames is higher with the morph (measured 0.018 against
// 0.010, 784 changed pixels a frame against 69): the morph spreads each level change over many
// frames, and the re-sampled heights of sliding vertices change the surface on the way. A finding
// of the metric, reported in docs/draw-paths.md, not asserted either way.
TEST(InstancedSchemes, WithoutTheMorphCdlodCracksAndPopsMore) {
  // cdlod-sse at 4 px: at 1 px this terrain is drawn almost all at the finest level, with no
  // transitions to crack or pop. 30 fps: popping compares a frame with the one before it (whichever
  // frames are measured), and the morph is meant to spread a level change over frames that close
  // together. Every 8th frame measured (68 of lowalt's 541): cdlod's worst pops with and without the
  // morph are the same as over every 2nd, at a third of the time (40 s against 105 s in Release).
  json schemes = json::array({{{"name", "cdlod"}, {"params", {{"morph_on", {0, 1}}}}},
                              {{"name", "cdlod-sse"}, {"params", {{"morph_on", {0, 1}}, {"max_error_px", 4}}}}});
  json cfg =
      smallRun("instanced-morph", {"paths/lowalt.csv"}, schemes, {{"every", 8}, {"passes", {"cracks", "popping"}}});
  cfg["resolution"] = {320, 180};
  cfg["fps"] = 30;
  std::map<std::string, json> byId;
  for (const json& c : lbtest::sweepCases(cfg, "instanced_morph"))
    byId[c["scheme"].get<std::string>() + (c["params"].value("morph_on", 1.0) == 0 ? "-off" : "-on")] = c;
  for (const char* scheme : {"cdlod", "cdlod-sse"}) {
    const json& off = byId[std::string(scheme) + "-off"];
    const json& on = byId[std::string(scheme) + "-on"];
    ASSERT_TRUE(off.is_object() && on.is_object()) << scheme;
    double cracksOff = 0, cracksOn = 0;
    for (auto [f, v] : lbtest::perFrame(off, "cracks_analytic")) cracksOff += v;
    for (auto [f, v] : lbtest::perFrame(on, "cracks_analytic")) cracksOn += v;
    EXPECT_GT(cracksOff, 0) << scheme << ": the planted defect (no morph) must be detected";
    EXPECT_EQ(cracksOn, 0) << scheme;
    auto stat = [](const json& c, const char* k, const char* s) { return c["summary"][k][s].get<double>(); };
    std::printf(
        "[Morph] %s lowalt: crack sites without morph %.0f; with/without morph: pop_mean mean %.4f/%.4f "
        "max %.4f/%.4f, pop_p99 max %.3f/%.3f, pop_changed mean %.1f/%.1f\n",
        scheme, cracksOff, stat(on, "pop_mean", "mean"), stat(off, "pop_mean", "mean"), stat(on, "pop_mean", "max"),
        stat(off, "pop_mean", "max"), stat(on, "pop_p99", "max"), stat(off, "pop_p99", "max"),
        stat(on, "pop_changed", "mean"), stat(off, "pop_changed", "mean"));
    if (std::string(scheme) == "cdlod") EXPECT_LE(stat(on, "pop_mean", "max"), 0.5 * stat(off, "pop_mean", "max"));
  }
}

// cdlod-sse's bound: a drawn node's projected error is within max_error_px, and within (1 + morph)
// times it while the node morphs; a frame with a level-0 node over the bound is counted as unmet and
// left out. Measured on the shipped paths and on the real DEM crop.
TEST(InstancedSchemes, CdlodSseKeepsItsBoundWhereItCanBeMet) {
  const double tau = 2.0, mu = 0.3;
  json schemes = json::array({{{"name", "cdlod-sse"}, {"params", {{"max_error_px", tau}}}}});
  json cfg = smallRun("sse-bound", shippedPaths(), schemes, {{"every", 3}, {"passes", {"error"}}});
  json dem = cfg;
  TerrainSpec crop = lbtest::demCrop();
  dem["terrain"] = {{"type", "hgt"}, {"file", crop.file}, {"extent", crop.extent}, {"height_scale", crop.heightScale}};
  dem["paths"] = {"paths/flyover.csv", "paths/lowalt.csv", "paths/grazing.csv"};
  int checked = 0, unmet = 0;
  double worst = 0;
  for (const json* run : {&cfg, &dem})
    for (const json& c : lbtest::sweepCases(*run, run == &cfg ? "instanced_sse" : "instanced_sse-dem")) {
      std::map<int, double> unmetAt;
      for (auto [f, v] : lbtest::perFrame(c, "cdlod_sse_unmet_nodes")) unmetAt[f] = v;
      for (auto [f, err] : lbtest::perFrame(c, "err_max_px")) {
        if (unmetAt.count(f) && unmetAt[f] > 0) {
          ++unmet;
          continue;
        }
        EXPECT_LE(err, 1.05 * (1 + mu) * tau) << c["case_id"] << " frame " << f;
        worst = std::max(worst, err / tau);
        ++checked;
      }
    }
  std::printf("[CdlodSse] %d frames within the bound (worst err_max/bound %.3f), %d unmet frames left out\n", checked,
              worst, unmet);
  EXPECT_GT(checked, 40);
}

namespace {
class InstancedGpu : public lbtest::GpuTest {};
}  // namespace

// What the CPU selected is what the GPU drew: clip invocations equal the sum over footprints of
// instances x triangles, and every drawn vertex lies on the finest lattice (no swimming: clipmap
// levels snap to their own spacing, CDLOD nodes to theirs, morphs slide along lattice lines only at
// full morph ends, which this does not check), for every instanced scheme on flyover and lowalt.
TEST_F(InstancedGpu, DrawnTrianglesAreTheSelectedOnesAndClipmapVerticesSitOnTheLattice) {
  const Heightfield& hf = lbtest::testTerrain();
  const double cell = double(hf.extent) / double(hf.width - 1);
  for (const std::string& name : instancedSchemes()) {
    if (findScheme(name)->info().path != DrawPath::InstancedGrid) continue;  // a CPU selection to compare
    const Scheme& scheme = *findScheme(name);
    Renderer r(lbtest::gpu(), hf, {160, 90, 16});
    r.setScheme(scheme, {});
    auto lod = scheme.instancedLod(hf, r.params());
    for (const char* pathName : {"flyover", "lowalt"}) {
      CameraPath path = loadCameraPath(kConfigs + "/paths/" + pathName + ".csv");
      const int n = frameCount(path, 30);
      for (int f = 0; f < n; f += n / 6) {
        CameraPose pose = samplePose(path, 30, f, hf);
        FrameResult fr = lbtest::renderOnce(r, pose);
        uint64_t predicted = 0;
        const Selection& sel = r.lastSelection();
        for (size_t k = 0; k < sel.instances.size(); ++k)
          predicted += sel.instances[k].size() * (lod->footprints()[k].indices.size() / 3);
        EXPECT_EQ(fr.stats.clipInvocations, predicted) << name << " " << pathName << " frame " << f;
        if (name != "clipmap") continue;
        r.measureHistogram(pose, pose);
        long off = 0;
        for (const glm::vec3& v : r.capturedMesh())
          for (double c : {double(v.x) / cell, double(v.z) / cell}) off += c != std::floor(c);
        EXPECT_EQ(off, 0) << pathName << " frame " << f << ": vertices off the lattice";
      }
    }
  }
}

// Clipmap's negative control: without the strip of zero-area triangles the T-junctions between
// levels are open, and the drawn-mesh check finds them; with it there are none.
TEST_F(InstancedGpu, ClipmapWithoutItsStripCracks) {
  const Heightfield& hf = lbtest::testTerrain();
  const glm::vec2 lo(0.0f);
  long with = 0, without = 0;
  for (int strip : {1, 0}) {
    Renderer r(lbtest::gpu(), hf, {160, 90, 16});
    r.setScheme(*findScheme("clipmap"), {{"strip", strip}, {"block", 8}});
    CameraPath path = loadCameraPath(kConfigs + "/paths/flyover.csv");
    for (int f = 0; f < frameCount(path, 30); f += 40) {
      CameraPose pose = samplePose(path, 30, f, hf);
      r.measureHistogram(pose, pose);
      long sites = meshCracks(r.capturedMesh(), {lo, lo + glm::vec2(hf.extent)}).crackSites;
      (strip ? with : without) += sites;
    }
  }
  EXPECT_EQ(with, 0);
  EXPECT_GT(without, 0);
}
