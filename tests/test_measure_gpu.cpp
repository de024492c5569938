// The two measurement paths (replay/measure_gpu.h): frames reduced on the GPU against frames read
// back and reduced on the CPU, through measureFrame on the same renderer and poses, on every shipped
// path over the procedural terrain and the committed DEM crop. Counts, histograms, cracks, coverage,
// popping and the image metrics that rest on integer sums are equal; the error statistics, PSNR and
// SSIM are held to the tolerances this test states; the surplus search meets its own 2% criterion on both.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "config/config.h"
#include "config/measure_spec.h"
#include "dem_crop.h"
#include "gpu_fixture.h"
#include "metrics/raycast_shade.h"
#include "render/renderer.h"
#include "replay/measure.h"
#include "replay/measure_gpu.h"
#include "replay/raycast_cache.h"
#include "results/run_dir.h"
#include "schemes/registry.h"
#include "shaders/raycast_params.h"
#include "sweep/runner.h"
#include "terrain/heightfield.h"

using namespace lb;

namespace {

std::map<std::string, double> valuesOf(const FrameMetrics& m) {
  std::map<std::string, double> v;
  for (const auto& [k, x] : m.values) v[k] = x;
  return v;
}

bool both(double a, double b) {
  return std::isnan(a) == std::isnan(b);
}

struct Worst {
  double err = 0, psnr = 0, ssim = 0, surplus = 0;
  int frames = 0, surplusFrames = 0;
};

// One frame measured both ways; every value compared under its rule.
void compareFrame(Renderer& r, const Scheme& scheme, const Heightfield& hf, const CameraPose& prev,
                  const CameraPose& pose, int frame, const std::string& where, Worst& worst) {
  MeasureSpec cpu;
  cpu.every = 1;
  cpu.compute = "cpu";
  MeasureSpec gpuSpec = cpu;
  gpuSpec.compute = "gpu";
  ReferenceCache refsCpu, refsGpu;
  const auto a = valuesOf(measureFrame(lbtest::gpu(), r, scheme, r.params(), hf, "t", cpu, refsCpu, frame, prev, pose));
  const auto b =
      valuesOf(measureFrame(lbtest::gpu(), r, scheme, r.params(), hf, "t", gpuSpec, refsGpu, frame, prev, pose));
  ASSERT_EQ(a.size(), b.size()) << where;
  ++worst.frames;
  for (const auto& [k, x] : a) {
    ASSERT_TRUE(b.count(k)) << where << " " << k;
    const double y = b.at(k);
    EXPECT_TRUE(both(x, y)) << where << " " << k << ": " << x << " vs " << y;
    if (std::isnan(x) || std::isnan(y)) continue;
    if (k.rfind("err_", 0) == 0) {  // within 0.5% or 1e-3 px
      EXPECT_LE(std::abs(x - y), std::max(0.005 * std::abs(x), 1e-3)) << where << " " << k;
      worst.err = std::max(worst.err, std::abs(x - y) / std::max(std::abs(x), 1e-12));
    } else if (k == "img_psnr_db") {
      EXPECT_LE(std::abs(x - y), 0.05) << where;
      worst.psnr = std::max(worst.psnr, std::abs(x - y));
    } else if (k == "img_ssim") {
      EXPECT_LE(std::abs(x - y), 1e-4) << where;
      worst.ssim = std::max(worst.ssim, std::abs(x - y));
    } else if (k == "flip_mean") {  // per pixel within 1e-4 (tests/test_gpu_flip.cpp), the mean within 1e-6
      EXPECT_LE(std::abs(x - y), 1e-4) << where;
    } else if (k == "flip_p95") {  // and the reduction's p95 within 2^-10 of its value
      EXPECT_LE(std::abs(x - y), x / 1024 + 1e-4) << where;
    } else if (k.rfind("surplus", 0) == 0) {
      continue;  // below: each path against its own criterion
    } else {
      EXPECT_EQ(x, y) << where << " " << k;  // counts, histograms, cracks, coverage, popping, MAD
    }
  }
  // The search's acceptance: a matched bound's p95 within 2% of the frame's own p95 on either path
  // (the GPU's p95s carry the histogram's 2^-10, hence the extra 0.2%).
  auto at = [](const std::map<std::string, double>& v, const char* k) {
    return v.count(k) ? v.at(k) : std::nan("");  // surplus is not searched without terrain on screen
  };
  for (const auto* v : {&a, &b}) {
    if (std::isnan(at(*v, "err_p95_px")) || at(*v, "surplus_matched") != 1) continue;
    EXPECT_LE(std::abs(at(*v, "surplus_p95_px") - at(*v, "err_p95_px")), 0.022 * at(*v, "err_p95_px")) << where;
  }
  if (!std::isnan(at(a, "surplus")) && !std::isnan(at(b, "surplus"))) {
    ++worst.surplusFrames;
    worst.surplus = std::max(worst.surplus, std::abs(at(a, "surplus") / at(b, "surplus") - 1));
  }
}

void everyShippedPath(const Heightfield& hf, const char* schemeName, const char* label) {
  Renderer r(lbtest::gpu(), hf, {160, 90, 16});
  const Scheme& scheme = *findScheme(schemeName);
  r.setScheme(scheme, {});
  Worst worst;
  for (const std::string& file : lbtest::shippedPathFiles()) {
    const CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + file);
    const int frames = frameCount(path, 30);
    for (int f : {0, frames / 2, frames - 1}) {
      const CameraPose prev = samplePose(path, 30, std::max(0, f - 1), hf), pose = samplePose(path, 30, f, hf);
      compareFrame(r, scheme, hf, prev, pose, f, std::string(label) + " " + file + " frame " + std::to_string(f),
                   worst);
    }
  }
  std::printf(
      "[measure gpu] %s, %s: %d frames; worst err_* %.2e relative, PSNR %.2e dB, SSIM %.2e; surplus on %d frames, "
      "paths apart by %.1f%% at most\n",
      label, schemeName, worst.frames, worst.err, worst.psnr, worst.ssim, worst.surplusFrames, 100 * worst.surplus);
}

}  // namespace

class MeasureGpuTest : public lbtest::GpuTest {};

TEST_F(MeasureGpuTest, AutoPicksTheCpuPathOnACpuRasterizerAndTheGpuElsewhere) {
  MeasureSpec s;
  const bool cpu = lbtest::gpu().props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  EXPECT_EQ(measureOnGpu(s, lbtest::gpu()), !cpu);
  s.compute = "gpu";
  EXPECT_TRUE(measureOnGpu(s, lbtest::gpu()));
  s.compute = "cpu";
  EXPECT_FALSE(measureOnGpu(s, lbtest::gpu()));
}

TEST_F(MeasureGpuTest, MatchesTheCpuPathOnEveryShippedPathOverProceduralTerrain) {
  everyShippedPath(lbtest::testTerrain(), "sphere", "procedural 129");
}

TEST_F(MeasureGpuTest, MatchesTheCpuPathOnEveryShippedPathOverTheDemCrop) {
  const Heightfield hf = makeHeightfield(lbtest::demCrop());
  everyShippedPath(hf, "cdlod", "DEM crop 601");
}

// Without a read-back the GPU path still finds a planted hole: the crack candidates send the frame
// to the CPU's flood fill, which counts it as the CPU path does.
TEST_F(MeasureGpuTest, CrackCandidatesSendAFrameToTheFloodFill) {
  const Heightfield& hf = lbtest::testTerrain();
  Renderer r(lbtest::gpu(), hf, {160, 90, 16});
  r.setScheme(*findScheme("sphere"), {});
  MeasureSpec spec;
  spec.every = 1;
  spec.passes = {"cracks"};
  spec.compute = "gpu";
  ReferenceCache refs;
  const CameraPose pose = lbtest::overviewPose();
  FrameMetrics clean = measureFrame(lbtest::gpu(), r, *findScheme("sphere"), r.params(), hf, "t", spec, refs, 0, pose,
                                    pose, nullptr, /*keepPixels=*/true);
  ASSERT_FALSE(clean.shaded.px.empty());
  EXPECT_EQ(valuesOf(clean).at("cracks_pixels"), 0);
  EXPECT_EQ(clean.crackMask.size(), size_t(160 * 90));
  // The same frame with a 3x1 hole punched into the terrain, uploaded as the live frame.
  RgbaImage holed = clean.shaded;
  int punched = 0;
  for (int y = 40; y < 50 && !punched; ++y)
    for (int x = 60; x < 100 && !punched; ++x) {
      bool inside = true;
      for (int dy = -4; dy <= 4; ++dy)
        for (int dx = -4; dx <= 6; ++dx) inside = inside && !isClear(holed, x + dx, y + dy);
      if (!inside) continue;
      for (int k = 0; k < 3; ++k)
        std::copy(kClearRgba.begin(), kClearRgba.end(), &holed.px[size_t(y * 160 + x + k) * 4]);
      punched = 3;
    }
  ASSERT_EQ(punched, 3) << "premise: terrain all around the hole";
  MeasureGpu& g = refs.gpu(lbtest::gpu(), hf, "t", 160, 90);
  g.castTruth(hf, pose);
  const GpuImageStats s = g.reduce.compare(g.reduce.upload(holed), g.truth, 16, false);
  const GpuImageStats before = g.reduce.compare(g.shaded, g.truth, 16, false);
  EXPECT_EQ(s.crackCandidates, before.crackCandidates + 3);
  EXPECT_EQ(crackPixels(holed, g.readImage(g.truth)), 3);
}

// run.json and every case record say where a measured frame's time went, pass by pass: the passes
// that ran and no other, each frame counted, the parts summing to the whole; the GPU path's one-off
// set-up is its own entry, charged once.
TEST_F(MeasureGpuTest, RunAndCaseRecordsCarryTheCostOfEachPass) {
  namespace fs = std::filesystem;
  for (const char* compute : {"cpu", "gpu"}) {
    const fs::path run = fs::path(::testing::TempDir()) / "lodbench_measure_costs" / compute;
    fs::remove_all(run);
    const Config config =
        parseConfig(std::string(R"({"name": "costs", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0,
                        "max_frames": 3, "terrain": {"type": "procedural", "size": 33, "seed": 5},
                        "paths": ["paths/flyover.csv"], "schemes": ["sphere"],
                        "measure": {"every": 1, "passes": ["error", "image", "popping"], "compute": ")") +
                        compute + R"("}})",
                    "costs.json", std::string(LODBENCH_SOURCE_DIR) + "/configs");
    RunOptions options{run.string(), false, false};
    ASSERT_EQ(runSweep(config, options).ok, 1) << compute;
    const nlohmann::json rj = readJsonFile((run / "run.json").string())["measure_costs_ms"];
    EXPECT_EQ(rj["frames"], 3) << compute;
    std::set<std::string> passes;
    double sum = 0;
    for (auto& [pass, ms] : rj["passes"].items()) {
      passes.insert(pass);
      EXPECT_GE(ms.get<double>(), 0.0) << pass;
      sum += ms.get<double>();
    }
    std::set<std::string> ran = {"render", "error", "ray_cast", "image", "flip", "popping"};
    if (std::string(compute) == "gpu") ran.insert("setup");
    EXPECT_EQ(passes, ran) << compute << ": " << rj.dump();
    EXPECT_NEAR(rj["measured_frame"].get<double>(), sum, 1e-9 * sum);
    const nlohmann::json cj = readCaseFiles(run.string()).at(0).doc["measure_costs_ms"];
    EXPECT_EQ(cj, rj) << "one case: its record's costs are the run's";
  }
}

// A terrain past the GPU ray cast's limits (here a strip one cell wider than its shader takes, in
// pages) has no truth on the GPU path: the histogram and error passes measure it, the passes that
// compare with the truth are null with the reason, and the frame is not lost.
TEST_F(MeasureGpuTest, ATerrainPastTheRayCastMeasuresWhatNeedsNoTruth) {
  Heightfield hf;
  hf.width = LB_RAYCAST_MAX_CELLS + 2;
  hf.height = 3;
  hf.extent = float(hf.width - 1);
  hf.page = 1023;
  hf.h.resize(size_t(hf.width) * size_t(hf.height));
  for (size_t i = 0; i < hf.h.size(); ++i) hf.h[i] = float(i % 97) * 0.05f;
  hf.updateRange();
  Renderer r(lbtest::gpu(), hf, {160, 90, 4});
  r.setScheme(*findScheme("uniform"), {});
  MeasureSpec spec;
  spec.every = 1;
  spec.passes = {"histogram", "error", "image", "cracks"};
  spec.compute = "gpu";
  ReferenceCache refs;
  const CameraPose pose = lbtest::poseAt({100, 40, -30}, {400, 0, 1});
  const FrameMetrics m =
      measureFrame(lbtest::gpu(), r, *findScheme("uniform"), r.params(), hf, "strip", spec, refs, 0, pose, pose);
  const auto v = valuesOf(m);
  EXPECT_GT(v.at("hist_0") + v.at("hist_1") + v.at("hist_2") + v.at("hist_3"), 0);  // triangles were counted
  EXPECT_TRUE(std::isfinite(v.at("err_p95_px")));
  EXPECT_TRUE(std::isnan(v.at("img_psnr_db")));
  EXPECT_TRUE(std::isnan(v.at("cracks_pixels")));
  EXPECT_TRUE(std::isfinite(v.at("cracks_analytic")));
  ASSERT_TRUE(m.unavailable.count("image"));
  EXPECT_NE(m.unavailable.at("image").find("ray cast"), std::string::npos) << m.unavailable.at("image");
  EXPECT_TRUE(m.unavailable.count("cracks_pixels"));
}
