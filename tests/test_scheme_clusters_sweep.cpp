// clusters (schemes/clusters.cpp) on lavapipe: the drawn vertices are the DAG's samples, and sweeps
// find no crack site or crack pixel and err_max_px within the stated factor of max_error_px on
// frames without unmet clusters: a cheap one (two views of a small terrain) and a heavy one
// (ClustersSweep.FullSweep: every view that stresses the bound, procedural and SRTM crop).
// InstancedSchemes.* checks every shipped path and scenario; the DAG itself:
// tests/test_scheme_clusters.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "camera/camera_path.h"
#include "config/config.h"
#include "dem_crop.h"
#include "gpu_fixture.h"
#include "render/renderer.h"
#include "render/scheme.h"
#include "schemes/registry.h"
#include "sweep/runner.h"
#include "terrain/heightfield.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";

class ClustersGpu : public lbtest::GpuTest {};

std::vector<json> sweep(const json& cfg, const std::string& tag) {
  Config c = parseConfig(cfg.dump(), tag + ".json", kConfigs);
  fs::path dir = fs::path(::testing::TempDir()) / ("lodbench_clusters_" + tag + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  RunOptions o;
  o.outDir = dir.string();
  o.progress = false;
  o.validation = std::getenv("LODBENCH_VALIDATION") != nullptr;
  RunTotals t = runSweep(c, o);
  EXPECT_EQ(t.failed, 0) << tag;
  EXPECT_EQ(t.validationErrors, 0) << tag;
  std::vector<json> cases;
  for (const auto& e : fs::directory_iterator(dir / "cases")) cases.push_back(json::parse(std::ifstream(e.path())));
  fs::remove_all(dir);
  return cases;
}

std::map<int, double> perFrame(const json& c, const std::string& key) {
  std::map<int, double> out;
  for (const json& f : c["frames"])
    if (f.contains(key) && f[key].is_number()) out[f["frame"].get<int>()] = f[key].get<double>();
  return out;
}

// The stated factor, as chunked's: a vertical error e at distance D >= the box distance projects to
// at most e K (1 + tx^2 + ty^2) / D px, tx and ty the tangents of the half fields of view
// (docs/draw-paths.md); the widest fov of a path gives its factor.
struct SweepFigures {
  int closed = 0, checked = 0, unmet = 0;
  double worst = 0;
};
SweepFigures checkSweep(json cfg, const std::vector<std::string>& pathNames, bool dem, const std::string& tag) {
  const double tau = cfg["schemes"][0]["params"]["max_error_px"], width = cfg["resolution"][0],
               height = cfg["resolution"][1];
  std::map<std::string, double> factor;
  cfg["paths"] = json::array();
  for (const std::string& name : pathNames) {
    cfg["paths"].push_back("paths/" + name + ".csv");
    double fov = 0;
    for (const auto& k : loadCameraPath(kConfigs + "/paths/" + name + ".csv").keys) fov = std::max(fov, k.fovDeg);
    const double ty = std::tan(fov * M_PI / 360.0), tx = ty * width / height;
    factor[name] = 1 + tx * tx + ty * ty;
  }
  if (dem) {
    const TerrainSpec crop = lbtest::demCrop();
    cfg["terrain"] = {
        {"type", "hgt"}, {"file", crop.file}, {"extent", crop.extent}, {"height_scale", crop.heightScale}};
  }
  SweepFigures s;
  for (const json& c : sweep(cfg, tag)) {
    const std::string id = c["case_id"];
    EXPECT_EQ(c["status"], "ok") << id << ": " << c["reason"];
    double f = 0;
    for (const auto& [name, v] : factor)
      if (id.find(name) != std::string::npos) f = std::max(f, v);
    EXPECT_GT(f, 1.0) << id;
    for (auto [fr, v] : perFrame(c, "cracks_analytic")) EXPECT_EQ(v, 0) << id << " frame " << fr;
    for (auto [fr, v] : perFrame(c, "cracks_pixels")) EXPECT_EQ(v, 0) << id << " frame " << fr;
    s.closed += int(perFrame(c, "cracks_analytic").size());
    const std::map<int, double> unmetAt = perFrame(c, "clusters_unmet_clusters");
    for (auto [fr, err] : perFrame(c, "err_max_px")) {
      if (unmetAt.count(fr) && unmetAt.at(fr) > 0) {
        ++s.unmet;
        continue;
      }
      EXPECT_LE(err, f * tau) << id << " frame " << fr;
      s.worst = std::max(s.worst, err / tau);
      ++s.checked;
    }
  }
  std::printf("[Clusters] %s: %d frames closed; %d within the factor (worst err_max/bound %.3f), %d unmet left out\n",
              tag.c_str(), s.closed, s.checked, s.worst, s.unmet);
  return s;
}

json sweepConfig(int size, double fps, int every) {
  return {{"name", "clusters"},
          {"resolution", {160, 90}},
          {"grid", 16},
          {"fps", fps},
          {"warmup_frames", 0},
          {"repetitions", 1},
          {"terrain", {{"type", "procedural"}, {"size", size}, {"seed", 3}, {"extent", 1000}, {"height_scale", 150}}},
          {"schemes", {{{"name", "clusters"}, {"params", {{"max_error_px", 2.0}}}}}},
          {"measure", {{"every", every}, {"passes", {"cracks", "error"}}}}};
}

}  // namespace

// The drawn mesh as the GPU placed it: every vertex at its heightfield sample.
TEST_F(ClustersGpu, DrawnVerticesAreSamples) {
  TerrainSpec spec;
  spec.size = 129;
  spec.seed = 3;
  spec.heightScale = 150.0f;
  const Heightfield hf = makeProcedural(spec);
  Renderer r(lbtest::gpu(), hf, {160, 90, 16});
  r.setScheme(*findScheme("clusters"), resolveParams(findScheme("clusters")->info(), {}));
  const CameraPose pose = samplePose(loadCameraPath(kConfigs + "/paths/edgeon.csv"), 4, 9, hf);
  r.measureHistogram(pose, pose);
  const std::vector<glm::vec3>& m = r.capturedMesh();
  ASSERT_GT(m.size(), 0u);
  const float cell = hf.extent / float(hf.width - 1);
  long off = 0;
  for (const glm::vec3& v : m) {
    const float gx = v.x / cell, gz = v.z / cell;
    const int x = int(std::lround(gx)), z = int(std::lround(gz));
    off += std::abs(gx - float(x)) > 1e-3f || std::abs(gz - float(z)) > 1e-3f || v.y != hf.at(x, z);
  }
  EXPECT_EQ(off, 0);
}

// Cheap: two views on a small procedural terrain, a few measured frames.
TEST(ClustersSweep, ClosedAndWithinTheStatedFactor) {
  const SweepFigures s = checkSweep(sweepConfig(129, 2, 4), {"flyover", "lowalt"}, false, "cheap");
  EXPECT_GT(s.closed, 4);
  EXPECT_GT(s.checked, 2);
}

// Heavy: every view that stresses the bound on the procedural terrain and the SRTM crop.
TEST(ClustersSweep, FullSweep) {
  SweepFigures s =
      checkSweep(sweepConfig(257, 4, 3), {"flyover", "lowalt", "grazing", "edgeon", "topdown"}, false, "paths");
  const SweepFigures d = checkSweep(sweepConfig(257, 4, 3), {"flyover", "lowalt"}, true, "dem");
  EXPECT_GT(s.closed + d.closed, 50);
  EXPECT_GT(s.checked + d.checked, 20);
}
