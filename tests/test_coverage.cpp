// Coverage error (metrics/coverage.h): terrain the scheme leaves out of a frame, or adds to it,
// against the ray-cast truth. Planted: a scheme that culls every patch, and a truth image with
// terrain removed from a region; both must be counted exactly, and the missing terrain must fail
// the case's summary and the compare gate instead of vanishing with the frame's null error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "compare/compare.h"
#include "gpu_fixture.h"
#include "metrics/coverage.h"
#include "replay/measure.h"
#include "report_fixture.h"
#include "results/write.h"
#include "shaders/shared.h"
#include "shaders/uniform_params.h"
#include "synthetic_run.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

// `uniform`, except that every patch gets level 0, which Vulkan discards: a LOD that culls every
// patch, visible or not. Never in the registry.
class CullEverything : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = [] {
      SchemeInfo i = findScheme("uniform")->info();
      i.name = "test-cull-everything";
      i.description = "TEST ONLY: uniform with every patch culled";
      return i;
    }();
    return kInfo;
  }
  void update(FrameUniforms& frame, const ParamValues& values) const override {
    Scheme::update(frame, values);
    frame.params[LB_UNIFORM_LEVEL / 4][LB_UNIFORM_LEVEL % 4] = 0.0f;
  }
};

const RgbaImage kClear{1, 1, {255, 0, 255, 255}};

// A w x h image: terrain (grey) where `terrain(x, y)`, clear magenta elsewhere.
template <class F>
RgbaImage image(int w, int h, F terrain) {
  RgbaImage img{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4, 255)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (!terrain(x, y)) {
        uint8_t* p = &img.px[(size_t(y) * size_t(w) + size_t(x)) * 4];
        p[0] = 255, p[1] = 0, p[2] = 255;
      } else {
        img.px[(size_t(y) * size_t(w) + size_t(x)) * 4 + 1] = 128;
      }
  return img;
}

// Clears the rectangle [x0, x1) x [y0, y1) of img to the clear colour.
void clearRect(RgbaImage& img, int x0, int y0, int x1, int y1) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) std::copy_n(kClear.px.begin(), 4, img.px.begin() + (y * img.width + x) * 4);
}

FrameMetrics measure(Renderer& r, const Scheme& s, const CameraPose& pose, ReferenceCache& refs) {
  MeasureSpec spec;
  spec.every = 1;
  spec.passes = {"error", "image"};
  return measureFrame(gpu(), r, s, r.params(), testTerrain(), "t", spec, refs, 0, pose, pose);
}

nlohmann::json summaryOf(const FrameMetrics& m) {
  CaseResult cr;
  cr.frames.push_back(FrameResult{m.frame, 1.0, 1.0, {}});
  cr.metrics = {m};
  return caseSummary(cr);
}

}  // namespace

TEST(Coverage, CountsMissingAndExtraPixelsExactly) {
  // Truth: terrain below row 10 of a 40 x 30 image. Frame: terrain below row 13 (3 rows missing)
  // and a 3 x 4 block of terrain in the truth's sky (12 extra).
  RgbaImage truth = image(40, 30, [](int, int y) { return y >= 10; });
  RgbaImage frame = image(40, 30, [](int x, int y) { return y >= 13 || (x < 3 && y < 4); });
  Coverage c = coverageError(frame, truth);
  EXPECT_EQ(c.truthTerrain, 40 * 20);
  EXPECT_EQ(c.missing, 40 * 3);
  EXPECT_EQ(c.extra, 3 * 4);
  Coverage same = coverageError(truth, truth);
  EXPECT_EQ(same.missing, 0);
  EXPECT_EQ(same.extra, 0);
  EXPECT_FALSE(coverageFailed(same));
  EXPECT_TRUE(coverageFailed(c)) << "120 of 800 truth pixels missing is over the tolerance";
  EXPECT_THROW(coverageError(frame, kClear), std::invalid_argument);
}

TEST(Coverage, ToleranceIsAFractionOfTheTruthsTerrain) {
  const double t = 1000, allowed = kCoverageTolerance * t;
  EXPECT_FALSE(coverageFailed(allowed, 0, t));
  EXPECT_TRUE(coverageFailed(allowed + 1, 0, t));
  EXPECT_TRUE(coverageFailed(0, allowed + 1, t));
  EXPECT_TRUE(coverageFailed(0, 1, 0)) << "terrain drawn where the truth shows none at all";
  EXPECT_TRUE(coverageFailed(t, 0, t)) << "nothing drawn";
}

class CoverageGpu : public lbtest::GpuTest {};

// The planted scheme draws nothing where the truth shows terrain: every truth-terrain pixel is
// missing, the frame's error is null (nothing drawn), yet the summary names the frame as a coverage
// failure and the compare gate fails the case against a baseline of the unplanted scheme.
TEST_F(CoverageGpu, SchemeCullingEveryPatchMissesAllTerrainAndFailsTheGate) {
  Renderer r(gpu(), testTerrain(), {96, 54, 8});
  ReferenceCache refs;
  const CullEverything cull;
  // A grazing view: the terrain fills the lower part of the frame up to a horizon.
  const CameraPose pose = lbtest::poseAt({-50, 140, -50}, {600, 60, 600});
  r.setScheme(cull, {});
  FrameMetrics culled = measure(r, cull, pose, refs);
  r.setScheme(*findScheme("uniform"), {});
  FrameMetrics drawn = measure(r, *findScheme("uniform"), pose, refs);

  const double truth = metricValue(culled, "coverage_truth_px");
  EXPECT_GT(truth, 1000) << "premise: the truth shows terrain";
  EXPECT_LT(truth, 96 * 54) << "premise: and sky";
  EXPECT_EQ(metricValue(culled, "coverage_missing_px"), truth);
  EXPECT_EQ(metricValue(culled, "coverage_extra_px"), 0);
  EXPECT_TRUE(culled.unavailable.count("error")) << "nothing drawn: err_* are null";
  EXPECT_EQ(metricValue(drawn, "coverage_truth_px"), truth);
  EXPECT_LE(metricValue(drawn, "coverage_missing_px"), kCoverageTolerance * truth);

  nlohmann::json bad = summaryOf(culled), good = summaryOf(drawn);
  EXPECT_EQ(bad["coverage_failed_frames"], nlohmann::json::array({0}));
  EXPECT_EQ(good["coverage_failed_frames"], nlohmann::json::array());
  EXPECT_EQ(bad["coverage_missing_px"]["max"].get<double>(), truth);
  EXPECT_EQ(bad["worst_frames"]["coverage_missing_px"], 0);

  using test::caseDoc, test::gpuTimes, test::runContext, test::writeRun;
  nlohmann::json base = caseDoc("x", gpuTimes(20, 1)), cand = base;
  base["summary"] = good;
  cand["summary"] = bad;
  CompareReport cr = compareRuns(loadRun(writeRun("cov_base", runContext(), {base})),
                                 loadRun(writeRun("cov_cand", runContext(), {cand})), {});
  ASSERT_EQ(cr.cases.size(), 1u);
  EXPECT_EQ(cr.exitCode(), 1);
  const std::vector<std::string>& why = cr.cases[0].regressions;
  EXPECT_NE(
      std::find(why.begin(), why.end(), "coverage: frame(s) 0 miss or add more than 10% of the truth's terrain pixels"),
      why.end());
  bool missingWorse = false;
  for (auto& a : cr.cases[0].accuracy) missingWorse |= a.metric == "coverage_missing_px" && a.worse;
  EXPECT_TRUE(missingWorse);
  // The unplanted scheme against itself passes.
  CompareReport same = compareRuns(loadRun(writeRun("cov_base", runContext(), {base})),
                                   loadRun(writeRun("cov_base2", runContext(), {base})), {});
  EXPECT_EQ(same.exitCode(), 0);
}

// Terrain removed from a region of the truth is extra terrain in the scheme's frame, pixel for pixel.
TEST_F(CoverageGpu, TerrainRemovedFromTheTruthIsCountedAsExtra) {
  Renderer r(gpu(), testTerrain(), {96, 54, 8});
  r.setScheme(*findScheme("uniform"), {});
  ReferenceCache refs;
  FrameMetrics m = measure(r, *findScheme("uniform"), lbtest::overviewPose(), refs);
  const Coverage before = coverageError(m.shaded, m.reference);
  RgbaImage planted = m.reference;
  const int x0 = 40, y0 = 20, x1 = 50, y1 = 28;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      ASSERT_TRUE(!isClear(m.shaded, x, y) && !isClear(m.reference, x, y)) << "premise: terrain in both at " << x;
  clearRect(planted, x0, y0, x1, y1);
  const Coverage after = coverageError(m.shaded, planted);
  EXPECT_EQ(after.extra, before.extra + (x1 - x0) * (y1 - y0));
  EXPECT_EQ(after.missing, before.missing);
  EXPECT_EQ(after.truthTerrain, before.truthTerrain - (x1 - x0) * (y1 - y0));
}

// Across devices a silhouette may rasterize a pixel apart: the case means may move by
// kCoverageSlackPx, no more.
TEST(Coverage, GateAllowsTheStatedSlackOnly) {
  using test::caseDoc, test::gpuTimes, test::runContext, test::writeRun;
  nlohmann::json base = caseDoc("x", gpuTimes(20, 1)), near = base, far = base;
  base["summary"] = {{"coverage_missing_px", {{"mean", 0.0}}}, {"coverage_failed_frames", nlohmann::json::array()}};
  near["summary"] = {{"coverage_missing_px", {{"mean", kCoverageSlackPx}}}};
  far["summary"] = {{"coverage_missing_px", {{"mean", kCoverageSlackPx + 0.5}}}};
  auto exitCode = [&](const nlohmann::json& c, const char* name) {
    return compareRuns(loadRun(writeRun("slack_base", runContext(), {base})),
                       loadRun(writeRun(name, runContext(), {c})), {})
        .exitCode();
  };
  EXPECT_EQ(exitCode(near, "slack_near"), 0);
  EXPECT_EQ(exitCode(far, "slack_far"), 1);
}

// A case whose summary lists coverage failures is shown as an accuracy failure: a row under Failed
// and skipped cases naming the frames, and named in the speed-vs-accuracy charts' caption.
TEST(Coverage, ReportShowsACoverageFailure) {
  namespace fs = std::filesystem;
  const fs::path run = test::copyFixture("lodbench_report_coverage");
  const std::string id = "sphere-tri_size8_proc129s1_flyover_96x54";
  auto plant = [](nlohmann::json& summary) {
    summary["coverage_failed_frames"] = {2};
    summary["coverage_missing_px"] = {{"mean", 900.0}, {"max", 1800.0}};
  };
  nlohmann::json all = test::readJson(run / "summary.json");
  for (auto& c : all["cases"])
    if (c["case_id"] == id) plant(c["summary"]);
  std::ofstream(run / "summary.json") << all.dump();
  nlohmann::json one = test::readJson(run / "cases" / (id + ".json"));
  plant(one["summary"]);
  std::ofstream(run / "cases" / (id + ".json")) << one.dump();

  test::writeNoHtml(run);
  const std::string md = test::readText(run / "report/report.md");
  EXPECT_NE(md.find("| `" + id +
                    "` | sphere | tri_size=8 | flyover | ok | accuracy: terrain missing or extra beyond 10% of the "
                    "truth's terrain pixels in measured frame(s) 2 |"),
            std::string::npos)
      << md.substr(md.find("Failed and skipped"), 1200);
  EXPECT_NE(md.find("Accuracy failures plotted by their drawn pixels only"), std::string::npos);
  EXPECT_NE(md.find("1800"), std::string::npos) << "the case table's missing terrain column";
}
