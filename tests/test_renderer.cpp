// Exact pipeline-statistics counters on lavapipe, draw splitting, sphere LOD behaviour, determinism.
#include <cmath>
#include <cstring>

#include "gpu_fixture.h"
#include "render/draw_limits.h"
#include "render/patch_grid.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

class Counters : public lbtest::GpuTest, public ::testing::WithParamInterface<int> {};

// uniform at integer level L on an N x N grid: N^2 patches, N^2 (L+1)^2 evaluation invocations,
// 2 N^2 L^2 clipping invocations, whatever the camera sees.
TEST_P(Counters, UniformLevelIsExact) {
  const int n = 4;
  const int level = GetParam();
  Renderer r(gpu(), testTerrain(), {64, 64, n});
  r.setScheme(*findScheme("uniform"), {{"level", level}});
  FrameResult f = lbtest::renderOnce(r, lbtest::overviewPose());
  const uint64_t n2 = n * n, l = uint64_t(level);
  EXPECT_EQ(f.stats.tcsPatches, n2);
  EXPECT_EQ(f.stats.tesInvocations, n2 * (l + 1) * (l + 1));
  EXPECT_EQ(f.stats.clipInvocations, 2 * n2 * l * l);
  // 16 patches at level 63 or 64 exceed 65,535 vertices: the split path is exercised.
  if (n2 * (l + 1) * (l + 1) > kMaxVerticesPerDraw) {
    EXPECT_GT(r.drawCount(), 1u);
  }
}
INSTANTIATE_TEST_SUITE_P(Levels, Counters, ::testing::Values(1, 2, 7, 16, 33, 63, 64));

TEST(DrawSplit, NoDrawExceedsVertexLimit) {
  for (float level : {1.0f, 7.5f, 31.0f, 64.0f})
    for (auto p : {Partitioning::Integer, Partitioning::FractionalEven, Partitioning::FractionalOdd}) {
      uint32_t perPatch = maxVerticesPerPatch(level, p);
      uint32_t perDraw = std::max(1u, kMaxVerticesPerDraw / perPatch);
      EXPECT_LE(perDraw * perPatch, kMaxVerticesPerDraw);
      EXPECT_GE(perPatch, uint32_t(std::pow(std::ceil(level) + 1, 2)));
    }
  EXPECT_EQ(maxVerticesPerPatch(64, Partitioning::Integer), 65u * 65u);
}

class SphereLod : public lbtest::GpuTest {};

TEST_F(SphereLod, LevelsFallAsCameraRecedes) {
  Renderer r(gpu(), testTerrain(), {160, 90, 16});
  r.setScheme(*findScheme("sphere"), {});
  uint64_t prevTris = UINT64_MAX;
  float prevMean = 1e9f;
  for (float dist : {300.0f, 600.0f, 1200.0f, 2400.0f}) {
    // Straight down over the centre: every patch stays in view as the camera climbs.
    glm::vec3 target(500, 0, 500);
    float fov = 2.0f * glm::degrees(std::atan(700.0f / dist));
    auto pose = lbtest::poseAt(target + glm::vec3(0, dist, 1), target, fov);
    FrameResult f = lbtest::renderOnce(r, pose);
    r.renderImage(pose, pose, RenderMode::Shaded);  // capture pass writes the factors
    auto levels = r.capturedLevels();
    double sum = 0;
    for (uint32_t p = 0; p < r.patchCount(); ++p) sum += levels[p * 8 + 4];
    float mean = float(sum / r.patchCount());
    EXPECT_LT(f.stats.clipInvocations, prevTris) << "at distance " << dist;
    EXPECT_LT(mean, prevMean) << "at distance " << dist;
    prevTris = f.stats.clipInvocations;
    prevMean = mean;
  }
}

TEST_F(SphereLod, CulledPatchesProduceNoTriangles) {
  Renderer r(gpu(), testTerrain(), {160, 90, 16});
  r.setScheme(*findScheme("sphere"), {});
  // Looking up and away from the terrain: every patch is outside the frustum.
  auto away = lbtest::poseAt({500, 400, 500}, {500, 2000, 3000});
  FrameResult f = lbtest::renderOnce(r, away);
  EXPECT_EQ(f.stats.tcsPatches, 16u * 16u);
  EXPECT_EQ(f.stats.clipInvocations, 0u);
  EXPECT_EQ(f.stats.tesInvocations, 0u);
  // Looking at one corner: only some patches produce triangles, and every culled one has level 0.
  auto corner = lbtest::poseAt({-50, 150, -50}, {100, 0, 100}, 30);
  r.renderImage(corner, corner, RenderMode::Shaded);
  auto levels = r.capturedLevels();
  int culled = 0;
  for (uint32_t p = 0; p < r.patchCount(); ++p) culled += levels[p * 8 + 4] == 0.0f;
  EXPECT_GT(culled, 0);
  EXPECT_LT(culled, int(r.patchCount()));
}

TEST_F(SphereLod, SameConfigSameCountersAndSameImage) {
  auto run = [](std::vector<uint8_t>* image) {
    Renderer r(gpu(), testTerrain(), {160, 90, 16});
    r.setScheme(*findScheme("sphere"), {{"tri_size", 4}});
    std::vector<PipelineStats> stats;
    for (int i = 0; i < 3; ++i) {
      auto pose = lbtest::poseAt({100.0f + 50 * i, 300, 100}, {600, 0, 700});
      stats.push_back(lbtest::renderOnce(r, pose).stats);
    }
    auto pose = lbtest::poseAt({100, 300, 100}, {600, 0, 700});
    *image = r.renderImage(pose, pose, RenderMode::Shaded);
    return stats;
  };
  std::vector<uint8_t> a, b;
  auto sa = run(&a), sb = run(&b);
  for (size_t i = 0; i < sa.size(); ++i) {
    EXPECT_EQ(sa[i].tcsPatches, sb[i].tcsPatches);
    EXPECT_EQ(sa[i].tesInvocations, sb[i].tesInvocations);
    EXPECT_EQ(sa[i].clipInvocations, sb[i].clipInvocations);
    EXPECT_EQ(sa[i].clipPrimitives, sb[i].clipPrimitives);
    EXPECT_EQ(sa[i].fsInvocations, sb[i].fsInvocations);
  }
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size())) << "second render differs";
  // Something was drawn: not every pixel is the clear colour.
  size_t terrainPixels = 0;
  for (size_t i = 0; i < a.size(); i += 4) terrainPixels += !(a[i] == 255 && a[i + 1] == 0 && a[i + 2] == 255);
  EXPECT_GT(terrainPixels, a.size() / 8);
}

TEST_F(SphereLod, SharedEdgesGetIdenticalLevels) {
  const int n = 16;
  Renderer r(gpu(), testTerrain(), {160, 90, n});
  r.setScheme(*findScheme("sphere"), {});
  auto pose = lbtest::poseAt({-100, 250, -100}, {500, 0, 500});
  r.renderImage(pose, pose, RenderMode::Shaded);
  auto lv = r.capturedLevels();
  int compared = 0;
  int visible = 0;
  for (uint32_t p = 0; p < r.patchCount(); ++p) visible += lv[p * 8 + 4] > 0;
  EXPECT_GT(visible, 0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float* p = &lv[size_t(j * n + i) * 8];
      if (i + 1 < n) {  // u=1 edge of (i,j) is the u=0 edge of (i+1,j)
        const float* q = &lv[size_t(j * n + i + 1) * 8];
        if (p[4] > 0 && q[4] > 0) {
          EXPECT_EQ(p[2], q[0]);
          ++compared;
        }
      }
      if (j + 1 < n) {  // v=1 edge of (i,j) is the v=0 edge of (i,j+1)
        const float* q = &lv[size_t((j + 1) * n + i) * 8];
        if (p[4] > 0 && q[4] > 0) {
          EXPECT_EQ(p[3], q[1]);
          ++compared;
        }
      }
    }
  EXPECT_GT(compared, 50);
}

TEST(Devices, RejectionReasonsAreReported) {
  auto devices = listDevices();
  ASSERT_FALSE(devices.empty());
  for (auto& d : devices) EXPECT_EQ(d.suitable, d.rejectReason.empty()) << d.name;
  Context ctx;
  try {
    createContext(ctx, {"no-such-gpu-xyz", false});
    FAIL() << "a device that does not exist was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-gpu-xyz"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find(devices[0].name), std::string::npos) << "lists every device";
  }
}
