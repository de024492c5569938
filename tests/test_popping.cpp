// Popping (docs/design.md, What is measured): the current pose rendered with the previous pose's LOD camera
// against live LOD. Only level changes may show up: a static camera and a camera-independent
// scheme give exactly zero, a jump in LOD gives a visible difference.
#include <cmath>

#include "config/config.h"
#include "gpu_fixture.h"
#include "metrics/image_metrics.h"
#include "replay/measure.h"
#include "replay/popping.h"
#include "results/write.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

constexpr int kW = 160, kH = 90, kGrid = 8;

// Low over the terrain looking down at it (no sky in view), and high above the far corner: the
// sphere LOD of the near patches differs by an order of magnitude between the two.
CameraPose nearPose() {
  return lbtest::poseAt({500, 300, 400}, {500, 0, 520});
}
CameraPose farPose() {
  return lbtest::poseAt({-1500, 2500, -1500}, {-3000, 0, -3000});
}

long clearPixels(const std::vector<uint8_t>& px) {
  RgbaImage img{kW, kH, px};
  long n = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) n += isClear(img, x, y);
  return n;
}

}  // namespace

class Popping : public lbtest::GpuTest {};

TEST_F(Popping, StaticCameraIsExactlyZero) {
  Renderer r(gpu(), testTerrain(), {kW, kH, kGrid});
  r.setScheme(*findScheme("sphere"), {});
  for (const CameraPose& pose : {nearPose(), lbtest::overviewPose()}) {
    PopResult p = measurePopping(r, pose, pose);
    EXPECT_EQ(p.mean, 0.0);
    EXPECT_EQ(p.p99, 0.0);
    EXPECT_EQ(p.changed, 0);
  }
}

// Sphere LOD frozen at a far camera is much coarser than live LOD at the near one: a sudden jump.
TEST_F(Popping, LodJumpShowsPopping) {
  Renderer r(gpu(), testTerrain(), {kW, kH, kGrid});
  r.setScheme(*findScheme("sphere"), {});
  PopResult p = measurePopping(r, farPose(), nearPose());
  EXPECT_GT(p.mean, 0.0);
  EXPECT_GT(p.p99, 0.0);
  EXPECT_GT(p.changed, 0);
  // The same figures compareImages gives for the two renders it describes.
  r.setCullCamera(Renderer::CullCamera::View);
  RgbaImage frozen{kW, kH, r.renderImage(nearPose(), farPose(), RenderMode::Shaded)};
  RgbaImage live{kW, kH, r.renderImage(nearPose(), nearPose(), RenderMode::Shaded)};
  ImageError e = compareImages(frozen, live);
  EXPECT_EQ(p.mean, e.meanAbsDiff);
  EXPECT_EQ(p.p99, e.p99AbsDiff);
  EXPECT_EQ(p.changed, e.changedPixels);
}

// uniform's levels do not depend on the camera: the frozen and live renders are identical.
TEST_F(Popping, CameraIndependentLodNeverPops) {
  Renderer r(gpu(), testTerrain(), {kW, kH, kGrid});
  r.setScheme(*findScheme("uniform"), {{"level", 5}});
  for (const CameraPose& previous : {farPose(), lbtest::overviewPose()}) {
    PopResult p = measurePopping(r, previous, nearPose());
    EXPECT_EQ(p.mean, 0.0);
    EXPECT_EQ(p.p99, 0.0);
    EXPECT_EQ(p.changed, 0);
  }
}

// Culling follows the LOD camera by default: frozen at a camera looking away, every patch would be
// culled and the pass would measure holes, not popping. measurePopping culls with the projection
// camera and restores the renderer's setting.
TEST_F(Popping, CullsWithTheLiveCameraAndRestoresTheSetting) {
  Renderer r(gpu(), testTerrain(), {kW, kH, kGrid});
  r.setScheme(*findScheme("sphere"), {});
  ASSERT_EQ(clearPixels(r.renderImage(nearPose(), nearPose(), RenderMode::Shaded)), 0) << "premise: no sky";
  EXPECT_EQ(clearPixels(r.renderImage(nearPose(), farPose(), RenderMode::Shaded)), long(kW) * kH);
  r.setCullCamera(Renderer::CullCamera::View);
  EXPECT_EQ(clearPixels(r.renderImage(nearPose(), farPose(), RenderMode::Shaded)), 0);
  r.setCullCamera(Renderer::CullCamera::Lod);
  measurePopping(r, farPose(), nearPose());
  EXPECT_EQ(r.cullCamera(), Renderer::CullCamera::Lod);
}

// A case's first frame has no previous frame: popping is null there, not 0, and summaries average
// only the frames that could pop.
TEST_F(Popping, FirstFrameIsNullAndSummariesSkipIt) {
  Renderer r(gpu(), testTerrain(), {kW, kH, kGrid});
  r.setScheme(*findScheme("sphere"), {});
  MeasureSpec spec;
  spec.every = 1;
  spec.passes = {"popping"};
  ReferenceCache refs;
  auto value = [](const FrameMetrics& m, const std::string& k) {
    for (auto& [name, v] : m.values)
      if (name == k) return v;
    ADD_FAILURE() << k << " missing";
    return 0.0;
  };
  FrameMetrics m0 = measureFrame(gpu(), r, *findScheme("sphere"), r.params(), testTerrain(), "t", spec, refs, 0,
                                 nearPose(), nearPose());
  FrameMetrics m10 = measureFrame(gpu(), r, *findScheme("sphere"), r.params(), testTerrain(), "t", spec, refs, 10,
                                  farPose(), nearPose());
  for (const char* k : {"pop_mean", "pop_p99", "pop_changed"}) EXPECT_TRUE(std::isnan(value(m0, k))) << k;
  const double pop10 = value(m10, "pop_mean");
  ASSERT_GT(pop10, 0.0) << "premise: frame 10 pops, so a fake 0 averaged in would show";

  CaseResult cr;
  for (int f : {0, 10}) cr.frames.push_back(FrameResult{f, 1.0, 1.0, {}});
  cr.metrics = {m0, m10};
  nlohmann::json summary = caseSummary(cr);
  EXPECT_EQ(summary["pop_mean"]["mean"].get<double>(), pop10);
  EXPECT_EQ(summary["pop_mean"]["max"].get<double>(), pop10);
  nlohmann::json cj = caseJson(Case{}, cr);
  EXPECT_TRUE(cj["frames"][0]["pop_mean"].is_null());
  EXPECT_TRUE(cj["frames"][0]["pop_changed"].is_null());
  EXPECT_EQ(cj["frames"][1]["pop_mean"].get<double>(), pop10);
  EXPECT_EQ(cj["image_reference"], kImageReference);
}
