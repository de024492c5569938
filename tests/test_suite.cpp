// The workload suite (configs/suite/). Its miniature (mini.json) runs on
// lavapipe as a check of the protocol, not of any verdict: every workload x scheme case ran or says
// why not, every repetition has the same frames, and `lodbench verdict` has one workload per
// terrain x view. The views defined above the ground keep their height and motion in sample
// spacings on terrains of very different extents; the GPU suite names every view on every
// terrain; scripts/run-suite.sh writes a config for a DEM in one command.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "camera/camera_path.h"
#include "cli_run.h"
#include "config/config.h"
#include "sweep/runner.h"
#include "terrain/heightfield.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kSrc = LODBENCH_SOURCE_DIR;
const std::string kSuite = kSrc + "/configs/suite";
const std::set<std::string> kViews = {"ground", "low", "grazing-flight", "flyover", "topdown", "dive", "turn180"};

std::string stem(const std::string& path) {
  return fs::path(path).stem().string();
}

TEST(Suite, GpuSuiteHasEveryViewOnEveryTerrain) {
  const Config gpu = loadConfig(kSuite + "/gpu.json"), mini = loadConfig(kSuite + "/mini.json");
  std::set<std::string> views, miniViews;
  for (const std::string& p : gpu.paths) views.insert(stem(p));
  for (const std::string& p : mini.paths) miniViews.insert(stem(p));
  EXPECT_EQ(views, kViews);
  EXPECT_EQ(miniViews, kViews) << "the miniature runs every view";
  EXPECT_EQ(gpu.resolutions, (std::vector<std::pair<int, int>>{{1920, 1080}}));
  EXPECT_EQ(gpu.repetitions, 3);
  EXPECT_EQ(gpu.match.metric, "err_p95_px");
  EXPECT_TRUE(gpu.match.tune);
  EXPECT_TRUE(mini.match.tune);
  // The committed SRTM crop (run-suite.sh swaps in the tile or a DEM), procedural with detail at
  // 4097^2, 16385^2 and an H100's largest, all at 1-4 m spacing, and canyon country.
  std::map<std::string, int> kinds;
  for (const TerrainSpec& t : gpu.terrains) {
    ++kinds[t.type];
    if (t.type == "hgt") EXPECT_EQ(fs::path(t.file).filename(), "N44W072_crop601.hgt");
    if (t.type != "procedural" && t.type != "canyon") continue;
    EXPECT_TRUE(t.detailToSpacing) << terrainLabel(t);
    const double spacing = t.extent / (t.size - 1);
    EXPECT_TRUE(spacing >= 1 && spacing <= 4) << terrainLabel(t) << ": " << spacing << " m";
  }
  EXPECT_EQ(kinds, (std::map<std::string, int>{{"hgt", 1}, {"procedural", 3}, {"canyon", 1}}));
  std::set<int> sizes;
  for (const TerrainSpec& t : gpu.terrains)
    if (t.type == "procedural") sizes.insert(t.size);
  EXPECT_EQ(sizes, (std::set<int>{4097, 16385, 32759}));
  EXPECT_EQ(expandCases(gpu).size(), gpu.terrains.size() * kViews.size() * gpu.schemes.size());
}

// Canyon country, the suite's terrain of another character: benches at the 6 levels k/5 of the
// height scale hold most samples, the walls between them are steeper than the procedural
// terrain's slopes, and the same spec gives the same bits.
TEST(Suite, CanyonIsTerracedAndDeterministic) {
  TerrainSpec spec;
  spec.type = "canyon";
  spec.size = 257;
  spec.seed = 2;
  spec.extent = 2560;
  spec.heightScale = 500;
  spec.detailToSpacing = true;
  EXPECT_EQ(terrainLabel(spec), "canyon257s2-detail");
  const Heightfield a = makeHeightfield(spec), b = makeHeightfield(spec);
  EXPECT_EQ(a.heightHash(), b.heightHash());
  EXPECT_GE(a.minHeight, 0.0f);
  EXPECT_LE(a.maxHeight, spec.heightScale);
  size_t onBench = 0;
  for (float h : a.h)
    for (int k = 0; k <= 5; ++k)
      if (std::fabs(h - spec.heightScale * float(k) / 5.0f) < 1e-3f) ++onBench;
  EXPECT_GT(double(onBench) / double(a.h.size()), 0.5) << "flat benches";
  auto steepest = [](const Heightfield& hf) {
    float s = 0;
    for (int z = 0; z < hf.height; ++z)
      for (int x = 1; x < hf.width; ++x) s = std::max(s, std::fabs(hf.at(x, z) - hf.at(x - 1, z)));
    return s;
  };
  TerrainSpec proc = spec;
  proc.type = "procedural";
  EXPECT_GT(steepest(a), 1.5f * steepest(makeHeightfield(proc))) << "walls steeper than the mountains' slopes";
}

// Sampled poses of one view on several terrains: height above the ground under the eye and the
// distance walked, both in sample spacings, frame by frame.
struct Track {
  std::vector<double> agl, dx, dz;
};
Track track(const CameraPath& path, const Heightfield& hf, double fps) {
  Track t;
  const double s = sampleSpacing(hf);
  const CameraPose first = samplePose(path, fps, 0, hf);
  for (int f = 0; f < frameCount(path, fps); ++f) {
    const CameraPose p = samplePose(path, fps, f, hf);
    t.agl.push_back((double(p.eye.y) - hf.sample(p.eye.x, p.eye.z)) / s);
    t.dx.push_back((double(p.eye.x) - first.eye.x) / s);
    t.dz.push_back((double(p.eye.z) - first.eye.z) / s);
  }
  return t;
}

TEST(Suite, GroundViewsKeepTheirHeightInSpacingsOnTerrainsOfVeryDifferentExtents) {
  // The miniature's two terrains (512 and 25,600 units) and the committed SRTM crop (54 km).
  const Config mini = loadConfig(kSuite + "/mini.json");
  std::vector<Heightfield> terrains;
  for (const TerrainSpec& t : mini.terrains) terrains.push_back(makeHeightfield(t));
  TerrainSpec crop;
  crop.type = "hgt";
  crop.file = kSrc + "/tests/data/N44W072_crop601.hgt";
  crop.extent = 54000;
  crop.heightScale = 1;
  terrains.push_back(makeHeightfield(crop));
  ASSERT_EQ(terrains.size(), 3u);
  EXPECT_GE(terrains[1].extent / terrains[0].extent, 50.0f);
  // ground: 2 spacings up on every frame; low: 6. The same walk in spacings everywhere.
  for (auto [view, height] : {std::pair<const char*, double>{"ground", 2.0}, {"low", 6.0}}) {
    SCOPED_TRACE(view);
    const CameraPath path = loadCameraPath(kSuite + "/paths/" + view + ".csv");
    const Track ref = track(path, terrains[0], 30);
    for (const Heightfield& hf : terrains) {
      const Track t = track(path, hf, 30);
      ASSERT_EQ(t.agl.size(), ref.agl.size());
      for (size_t f = 0; f < t.agl.size(); ++f) {
        // Float positions: a height of 2.4 km is resolved to 2^-12 m, 1e-4 of a 90 m spacing.
        ASSERT_NEAR(t.agl[f], height, 1e-3) << "extent " << hf.extent << " frame " << f;
        ASSERT_NEAR(t.agl[f], ref.agl[f], 1e-3) << "extent " << hf.extent << " frame " << f;
        ASSERT_NEAR(t.dx[f], ref.dx[f], 1e-3) << "extent " << hf.extent << " frame " << f;
        ASSERT_NEAR(t.dz[f], ref.dz[f], 1e-3) << "extent " << hf.extent << " frame " << f;
      }
    }
    if (std::string(view) == "ground") {  // 1.4 spacings per second: 14 in the 10 s walk
      const double walked = std::hypot(ref.dx.back(), ref.dz.back());
      EXPECT_GT(walked, 13.5);
      EXPECT_LT(walked, 14.0);
    }
  }
  // grazing flight: 0.004 extent above the ground, never under the clamp of 1 spacing.
  const CameraPath grazing = loadCameraPath(kSuite + "/paths/grazing-flight.csv");
  for (const Heightfield& hf : terrains)
    for (double agl : track(grazing, hf, 30).agl)
      ASSERT_GE(agl, std::max(kMinEyeAglSpacings, 0.004 * hf.extent / sampleSpacing(hf)) - 1e-3) << hf.extent;
}

// The miniature through a whole sweep, then its verdict through the CLI.
TEST(Suite, MiniatureRunsEveryWorkloadAndSchemeAndTheVerdictCoversThem) {
  const Config c = loadConfig(kSuite + "/mini.json");
  const fs::path dir = fs::path(::testing::TempDir()) / ("lodbench_suite_" + std::to_string(getpid()));
  fs::remove_all(dir);
  RunOptions o;
  o.outDir = dir.string();
  o.progress = false;
  o.validation = std::getenv("LODBENCH_VALIDATION") != nullptr;
  const RunTotals totals = runSweep(c, o);
  EXPECT_EQ(totals.validationErrors, 0);
  const std::vector<Case> cases = expandCases(c);
  ASSERT_EQ(cases.size(), c.terrains.size() * kViews.size() * c.schemes.size());

  // Every case ran (or failed with its reason); every repetition has the path's first frames.
  std::map<std::string, std::map<std::string, std::string>> offTarget;  // workload -> scheme -> why
  for (const Case& k : cases) {
    SCOPED_TRACE(k.id);
    const fs::path file = dir / "cases" / (k.id + ".json");
    ASSERT_TRUE(fs::exists(file));
    const json r = lb::test::readJson(file.string());
    if (r["status"] != "ok") {
      EXPECT_EQ(r["status"], "failed");
      EXPECT_FALSE(r["reason"].get<std::string>().empty());
      continue;
    }
    const int perRep = std::min(c.maxFrames, frameCount(loadCameraPath(k.path), c.fps));
    std::vector<int> frames;
    for (const json& f : r["frames"]) frames.push_back(f["frame"].get<int>());
    ASSERT_EQ(frames.size(), size_t(perRep * c.repetitions));
    for (size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(frames[i], int(i) % perRep);
    const json& m = r["matched"];
    ASSERT_TRUE(m.is_object());
    EXPECT_EQ(m["metric"], "err_p95_px");
    EXPECT_TRUE(m.contains("tuned"));
    // Off target: errs more at its finest setting (missing from the verdict), or is more accurate at
    // its coarsest (compared there, with a note).
    if (!m["reachable"].get<bool>())
      offTarget[k.terrainLabel + "_" + stem(k.path) + "_64x36"][k.scheme] =
          m["achieved"].get<double>() > m["target"].get<double>() ? "target unreachable" : "more accurate";
  }

  const lb::test::CliOut v = lb::test::lodbench("verdict " + dir.string(), false);
  ASSERT_EQ(v.code, 0) << v.text;
  const json verdict = lb::test::readJson((dir / "verdict.json").string());
  std::set<std::string> ids, expected;
  for (const TerrainSpec& t : c.terrains)
    for (const std::string& p : c.paths) expected.insert(terrainLabel(t) + "_" + stem(p) + "_64x36");
  int compared = 0;
  for (const json& w : verdict["workloads"]) {
    const std::string id = w["id"];
    SCOPED_TRACE(id);
    EXPECT_TRUE(ids.insert(id).second) << "one entry per workload";
    // Each scheme either has a cost ratio or is missing with its reason.
    for (const SchemeEntry& s : c.schemes) {
      const bool timed = w["ratio"].contains(s.name), missing = w["missing"].contains(s.name);
      EXPECT_NE(timed, missing) << s.name;
      if (missing) EXPECT_FALSE(w["missing"][s.name].get<std::string>().empty()) << s.name;
      const std::string why = offTarget[id].count(s.name) ? offTarget[id][s.name] : "";
      if (why == "target unreachable") {
        ASSERT_TRUE(missing) << s.name;
        EXPECT_EQ(w["missing"][s.name].get<std::string>().rfind("target unreachable", 0), 0u) << s.name;
      }
      if (why == "more accurate") {
        ASSERT_TRUE(timed) << s.name;
        ASSERT_TRUE(w.contains("notes") && w["notes"].contains(s.name)) << s.name;
        EXPECT_NE(w["notes"][s.name].get<std::string>().find("more accurate than the target"), std::string::npos);
      }
    }
    if (w["ratio"].size() >= 2) ++compared;
  }
  EXPECT_EQ(ids, expected);
  EXPECT_GE(compared, 1) << "at least one workload compares two schemes";
  int unreachable = 0, accurate = 0;
  for (auto& [w, schemes] : offTarget)
    for (auto& [scheme, why] : schemes) ++(why == "more accurate" ? accurate : unreachable);
  std::printf(
      "[suite] %zu cases, %zu workloads, %d with two or more schemes timed; off target: %d unreachable (missing), %d "
      "more accurate at their coarsest (compared with a note)\n",
      cases.size(), ids.size(), compared, unreachable, accurate);
}

// scripts/run-suite.sh: one command writes a config for a DEM (here the committed crop) from the
// suite and runs it (--dry-run here: it lists the cases without a device).
TEST(Suite, RunSuiteScriptWritesAConfigForADem) {
  if (lb::test::shell("command -v python3").code != 0) GTEST_SKIP() << "python3 missing: run-suite.sh needs it";
  const std::string out = lb::test::freshDir("suite_script");
  const std::string script = "LODBENCH=" + std::string(LODBENCH_BINARY) + " bash " + kSrc + "/scripts/run-suite.sh ";
  const lb::test::CliOut r =
      lb::test::shell(script + kSrc + "/tests/data/N44W072_crop601.hgt --extent 54000 --config " + kSuite +
                      "/mini.json --out " + out + "/dem --dry-run");
  ASSERT_EQ(r.code, 0) << r.text;
  EXPECT_NE(r.text.find("lodbench: 21 cases"), std::string::npos) << r.text;
  const json dem = lb::test::readJson(out + "/dem/config.json");
  ASSERT_EQ(dem["terrains"].size(), 1u);
  EXPECT_EQ(dem["terrains"][0]["type"], "hgt");
  EXPECT_EQ(dem["terrains"][0]["extent"], 54000.0);
  EXPECT_EQ(dem["paths"].size(), kViews.size());
  for (const json& p : dem["paths"]) EXPECT_TRUE(fs::exists(p.get<std::string>())) << p;
  EXPECT_FALSE(fs::exists(out + "/dem/run/run.json")) << "a dry run writes no run";

  // The GPU suite for a device that takes 12,513^2 (lavapipe's): its largest terrain becomes that
  // size at the same spacing, and the 16385^2 terrain that the device cannot take is left out.
  const lb::test::CliOut g =
      lb::test::shell(script + "--config " + kSuite + "/gpu.json --largest 12513 --out " + out + "/gpu --dry-run");
  ASSERT_EQ(g.code, 0) << g.text;
  EXPECT_NE(g.text.find("left out procedural 16385^2"), std::string::npos) << g.text;
  std::set<int> sizes;
  const json gpu = lb::test::readJson(out + "/gpu/config.json");
  for (const json& t : gpu["terrains"]) {
    if (t["type"] != "procedural") continue;
    sizes.insert(t["size"].get<int>());
    EXPECT_NEAR(t["extent"].get<double>() / (t["size"].get<double>() - 1), t["size"] == 4097 ? 2.0 : 1.0, 1e-9);
  }
  EXPECT_EQ(sizes, (std::set<int>{4097, 12513}));
  const lb::test::CliOut bad = lb::test::shell(script + kSrc + "/tests/data/N44W072_crop601.hgt --config " + kSuite +
                                               "/mini.json --out " + out + "/bad --dry-run");
  EXPECT_EQ(bad.code, 2) << bad.text;
  EXPECT_NE(bad.text.find("give its --extent"), std::string::npos) << bad.text;

  // The verdict at another target: the same suite with the match's value set, under its own name.
  const lb::test::CliOut half = lb::test::shell(
      script + "--config " + kSuite + "/mini.json --largest off --target 0.5 --out " + out + "/half --dry-run");
  ASSERT_EQ(half.code, 0) << half.text;
  const json h = lb::test::readJson(out + "/half/config.json");
  EXPECT_EQ(h["match"]["value"], 0.5);
  EXPECT_EQ(h["name"], "suite-mini-target0.5");
  EXPECT_NE(half.text.find("_match-err_p95_px0.5_tuned"), std::string::npos) << half.text;
  const lb::test::CliOut notANumber =
      lb::test::shell(script + "--config " + kSuite + "/mini.json --target px --out " + out + "/nan --dry-run");
  EXPECT_EQ(notANumber.code, 2) << notANumber.text;
  EXPECT_NE(notANumber.text.find("--target 'px': expected a number"), std::string::npos) << notANumber.text;
}

}  // namespace
