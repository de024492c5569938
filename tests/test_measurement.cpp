// Measurement passes: triangle-size histogram totals and screen-space error maps.
#include <cmath>

#include "config/config.h"
#include "gpu_fixture.h"
#include "replay/measure.h"
#include "results/write.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

class Measurement : public lbtest::GpuTest {};

// The histogram counts every generated triangle once: its total equals the clipping invocations
// of the bare timing frame with the same camera and LOD.
TEST_F(Measurement, HistogramTotalEqualsClippingInvocations) {
  for (const char* scheme : {"uniform", "sphere"}) {
    Renderer r(gpu(), testTerrain(), {160, 90, 16});
    r.setScheme(*findScheme(scheme), {});
    for (auto pose : {lbtest::overviewPose(), lbtest::poseAt({500, 60, -50}, {500, 40, 600}),
                      lbtest::poseAt({500, 400, 500}, {500, 2000, 3000})}) {
      FrameResult timed = lbtest::renderOnce(r, pose);
      FrameResult measured;
      TriangleHistogram h = r.measureHistogram(pose, pose, &measured);
      EXPECT_EQ(h.total(), timed.stats.clipInvocations) << scheme;
      EXPECT_EQ(measured.stats.tesInvocations, timed.stats.tesInvocations) << "same LOD in both passes";
    }
  }
}

TEST_F(Measurement, HistogramOfAKnownFlatGridIsExact) {
  // A flat terrain seen straight down: every triangle of uniform level L over an N x N grid has
  // the same screen area, so all land in one bin that can be computed by hand.
  Heightfield flat;
  flat.width = flat.height = 2;
  flat.extent = 1000;
  flat.h = {0, 0, 0, 0};
  flat.updateRange();
  const int n = 4, level = 6, w = 128, h = 128;
  Renderer r(gpu(), flat, {w, h, n});
  r.setScheme(*findScheme("uniform"), {{"level", level}});
  // fov chosen so the terrain spans exactly the viewport height: 1000 world units -> 128 px.
  float dist = 1000.0f;
  float fov = 2.0f * glm::degrees(std::atan(500.0f / dist));
  auto pose = lbtest::poseAt({500, dist, 500.001f}, {500, 0, 500}, fov);
  TriangleHistogram hist = r.measureHistogram(pose, pose);
  double side = 128.0 / (n * level);  // pixels per tessellated quad
  double area = side * side / 2.0;    // 14.2 px^2: mid-bin, away from the power-of-two edges
  int bin = int(std::floor(std::log2(area))) + 4;
  EXPECT_EQ(hist.bins[size_t(bin)], uint64_t(2 * n * n * level * level)) << "bin " << bin;
  EXPECT_EQ(hist.backfacing, 0u) << "seen from above, the terrain faces the camera";
  EXPECT_EQ(hist.offscreen, 0u);
  // Exact area sum: every triangle has the same area, in steps of 1/256 px^2.
  EXPECT_NEAR(hist.areaSum, 2.0 * n * n * level * level * area, 2.0 * n * n * level * level / 256.0);
}

TEST_F(Measurement, ErrorMapIsZeroForReferenceDenseAndLargerWhenCoarse) {
  Renderer r(gpu(), testTerrain(), {160, 90, 16});
  auto pose = lbtest::poseAt({-100, 300, -100}, {500, 0, 500});
  auto meanError = [&](int level) {
    r.setScheme(*findScheme("uniform"), {{"level", level}});
    auto err = r.renderErrorMap(pose, pose);
    double sum = 0;
    int n = 0;
    for (float e : err)
      if (e >= 0) sum += e, ++n;
    EXPECT_GT(n, 1000);
    return sum / n;
  };
  double coarse = meanError(1), fine = meanError(8);
  EXPECT_GT(coarse, fine * 2);
  EXPECT_GT(coarse, 0.5);
}

// A frame with nothing on screen (camera looking up into the sky) has no error and no triangle
// sizes: they are null with a reason in the frame record and the summary, never 0 or silently absent.
TEST_F(Measurement, NothingOnScreenGivesNullWithAReason) {
  Renderer r(gpu(), testTerrain(), {160, 90, 16});
  r.setScheme(*findScheme("uniform"), {});
  MeasureSpec spec;
  spec.every = 1;
  spec.passes = {"error", "histogram"};
  ReferenceCache refs;
  const CameraPose sky = lbtest::poseAt({500, 400, 500}, {500, 2000, 3000});
  const CameraPose ground = lbtest::overviewPose();
  FrameMetrics m =
      measureFrame(gpu(), r, *findScheme("uniform"), r.params(), testTerrain(), "t", spec, refs, 0, sky, sky);
  ASSERT_TRUE(m.hasHistogram);
  EXPECT_EQ(m.histogram.total(), m.histogram.offscreen + m.histogram.backfacing) << "premise: nothing on screen";
  EXPECT_NE(m.unavailable.at("error").find("no terrain pixel"), std::string::npos);
  EXPECT_NE(m.unavailable.at("triangle_sizes").find("no front-facing triangle"), std::string::npos);
  FrameMetrics g =
      measureFrame(gpu(), r, *findScheme("uniform"), r.params(), testTerrain(), "t", spec, refs, 1, ground, ground);
  EXPECT_TRUE(g.unavailable.empty()) << "a frame with terrain on screen has every value";
  CaseResult cr;
  for (int f : {0, 1}) cr.frames.push_back(FrameResult{f, 1.0, 1.0, {}});
  cr.metrics = {m, g};
  nlohmann::json cj = caseJson(Case{}, cr);
  EXPECT_TRUE(cj["frames"][0]["err_mean_px"].is_null());
  EXPECT_TRUE(cj["frames"][0]["tri_area_mean"].is_null());
  EXPECT_TRUE(cj["frames"][0]["unavailable"].contains("error"));
  EXPECT_FALSE(cj["frames"][1].contains("unavailable"));
  EXPECT_GT(cj["frames"][1]["err_mean_px"].get<double>(), 0.0);
  EXPECT_TRUE(caseSummary(cr)["unavailable"].contains("error"));
}
