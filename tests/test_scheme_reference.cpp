// reference scheme: integer level 64 everywhere and no culling, so the counters are the uniform
// formula at L = 64 whatever the camera sees: N^2 patches, N^2 (L+1)^2 evaluation invocations,
// 2 N^2 L^2 triangles.
#include "gpu_fixture.h"
#include "shaders/shared.h"
#include "vk/context.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

class ReferenceScheme : public lbtest::GpuTest {};

TEST_F(ReferenceScheme, CountersAreUniformLevel64EvenWhenLookingAway) {
  // Vulkan guarantees this limit, so min(64, limit) is 64.
  EXPECT_GE(gpu().props.limits.maxTessellationGenerationLevel, 64u);
  const uint64_t n = 4, l = 64;
  Renderer r(gpu(), testTerrain(), {64, 64, int(n)});
  r.setScheme(*findScheme("reference"), {});
  EXPECT_GT(r.drawCount(), 1u);                                    // 16 x 65^2 vertices exceed one draw's 65,535
  auto away = lbtest::poseAt({500, 400, 500}, {500, 2000, 3000});  // terrain entirely outside the view
  for (const CameraPose& pose : {lbtest::overviewPose(), away}) {
    FrameResult f = lbtest::renderOnce(r, pose);
    EXPECT_EQ(f.stats.tcsPatches, n * n);
    EXPECT_EQ(f.stats.tesInvocations, n * n * (l + 1) * (l + 1));
    EXPECT_EQ(f.stats.clipInvocations, 2 * n * n * l * l);
  }
  r.renderImage(away, away, RenderMode::Shaded);
  auto lv = r.capturedLevels();
  for (uint32_t p = 0; p < r.patchCount(); ++p)
    for (int k = 0; k < 6; ++k) EXPECT_EQ(lv[p * LB_CAPTURE_STRIDE + k], 64.0f) << "patch " << p << " level " << k;
}
