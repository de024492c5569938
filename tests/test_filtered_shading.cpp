// Filtered shading: the normal map's mip chain, the one footprint function (shaders/footprint.h)
// that the raster and both ray casts call, and what it buys: on a distant view the raster's shaded
// frame and its ray-cast truth agree better than when both shade from level 0, while geometry,
// counters and error maps stay exactly as they were.
#include <cmath>

#include "camera/camera_matrices.h"
#include "gpu_fixture.h"
#include "metrics/image_metrics.h"
#include "metrics/raycast.h"
#include "metrics/raycast_shade.h"
#include "shaders/footprint.h"
#include "terrain/generators.h"
#include "terrain/normal_map.h"

using namespace lb;
using lbtest::gpu;

namespace {

// Fine relief (fBm down to two sample spacings) that aliases when a pixel covers many texels.
const Heightfield& detailedTerrain() {
  static const Heightfield hf = [] {
    TerrainSpec s;
    s.size = 513;
    s.seed = 11;
    s.extent = 1000;
    s.heightScale = 120;
    s.detailToSpacing = true;
    return makeProcedural(s);
  }();
  return hf;
}

// The ray-cast truth shaded at a fixed level (level < 0: the footprint's, as raycastImage does).
RgbaImage truthAt(const Heightfield& hf, const CameraPose& pose, int w, int h, float level) {
  const MaxMipmap mip = buildMaxMipmap(hf);
  const NormalMap normals = computeNormalMap(hf);
  const CameraMatrices cam = cameraMatrices(pose, float(w) / float(h), hf.extent);
  const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.proj) * glm::dmat4(cam.view));
  const float angle = shadingPixelAngle(cam.proj, h);
  RgbaImage img{w, h, std::vector<uint8_t>(size_t(w) * size_t(h) * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      glm::dvec3 o, d;
      pixelRay(inv, x, y, w, h, o, d);
      const RayHit r = castRay(hf, mip, o, d, 0.0, 1.0);
      std::array<uint8_t, 4> c = kClearRgba;
      if (r.hit) {
        const glm::vec3 p(r.pos);
        const float l = level >= 0 ? level : shadingLevel(p, cam.eye, angle, hf.extent, hf.width, hf.height);
        c = shadeTerrain(normals, hf.extent, p.x, p.z, l);
      }
      std::copy(c.begin(), c.end(), img.px.begin() + long((size_t(y) * size_t(w) + size_t(x)) * 4));
    }
  return img;
}

class FilteredShading : public lbtest::GpuTest {};

}  // namespace

// The level grows by one per doubling of the distance along a fixed direction (exactly, at powers
// of two), is 0 up close, stops at the map's last level, and a grazing ray's stretch is capped.
TEST(ShadingLevel, OneLevelPerDoublingClampedToTheChain) {
  const float extent = 1024, angle = 1.0f / 256;  // 1025 samples: texel 1, 11 levels (0..10)
  const glm::vec3 eye(0, 0, 0), down = glm::normalize(glm::vec3(1, -1, 0));
  EXPECT_EQ(normalMapLevels(1025, 1025), 11);
  EXPECT_EQ(normalMapLevels(5, 3), 3);
  EXPECT_EQ(shadingLevel(eye + 10.0f * down, eye, angle, extent, 1025, 1025), 0.0f);
  float previous = -1;
  for (float d = 512; d <= 16384; d *= 2) {
    const float l = shadingLevel(eye + d * down, eye, angle, extent, 1025, 1025);
    if (previous > 0) EXPECT_NEAR(l, previous + 1.0f, 1e-4f) << d;
    EXPECT_GE(l, 0.0f);
    previous = l;
  }
  EXPECT_EQ(shadingLevel(eye + 1e6f * down, eye, angle, extent, 1025, 1025), 10.0f);
  // A ray at 1/1000 elevation is stretched as one at 1/64: the same level.
  const glm::vec3 flat = glm::normalize(glm::vec3(1, -0.001f, 0)), capped = glm::normalize(glm::vec3(1, -1.0f / 64, 0));
  EXPECT_NEAR(shadingLevel(eye + 2000.0f * flat, eye, angle, extent, 1025, 1025),
              shadingLevel(eye + 2000.0f * capped, eye, angle, extent, 1025, 1025), 0.02f);
  EXPECT_EQ(piecewiseLog2(1.0f), 0.0f);
  EXPECT_EQ(piecewiseLog2(8.0f), 3.0f);
  EXPECT_EQ(piecewiseLog2(12.0f), 3.5f);
}

// Vulkan's chain of sizes; each coarser texel the mean of the finer texels it covers (an odd
// level's last row and column join the texel before them); a plane's gradient at every level.
TEST(ShadingLevel, MipChainAveragesTheGradients) {
  Heightfield hf;
  hf.width = 5;
  hf.height = 3;
  hf.extent = 4;
  hf.h = {0, 1, 4, 9, 16, 2, 3, 6, 11, 18, 0, 5, 4, 3, 2};
  const NormalMap nm = computeNormalMap(hf);
  ASSERT_EQ(nm.levels(), 3);
  EXPECT_EQ(nm.levelWidth(1), 2);
  EXPECT_EQ(nm.levelHeight(1), 1);
  EXPECT_EQ(nm.levelWidth(2), 1);
  EXPECT_EQ(nm.levelHeight(2), 1);
  auto g = [&](int k, int x, int z, int c) {
    return halfToFloat(nm.levelTexels(k)[(size_t(z) * size_t(nm.levelWidth(k)) + size_t(x)) * 2 + size_t(c)]);
  };
  for (int c = 0; c < 2; ++c) {
    float mean = 0;  // level-1 texel (1, 0): columns 2..4 of rows 0..2
    for (int z = 0; z < 3; ++z)
      for (int x = 2; x < 5; ++x) mean += g(0, x, z, c) / 9.0f;
    EXPECT_NEAR(g(1, 1, 0, c), mean, 1e-3f * std::max(1.0f, std::fabs(mean)));
  }
  // A plane: every interior texel of every level holds its gradient, so a sample near the centre
  // at a level whose footprint stays inside reads the plane's normal (the borders' one-sided
  // differences differ).
  Heightfield plane;
  plane.width = 37;
  plane.height = 21;
  plane.extent = 36;
  for (int z = 0; z < 21; ++z)
    for (int x = 0; x < 37; ++x) plane.h.push_back(0.5f * float(x) - 0.45f * float(z));
  const NormalMap pm = computeNormalMap(plane);
  ASSERT_EQ(pm.levels(), 6);
  const glm::vec2 g0(halfToFloat(pm.texels[(10 * 37 + 18) * 2]), halfToFloat(pm.texels[(10 * 37 + 18) * 2 + 1]));
  EXPECT_FLOAT_EQ(g0.x, -0.5f);
  for (float level : {0.0f, 0.5f, 1.0f, 1.5f}) {
    const glm::vec3 n = sampleNormalMap(pm, 36, 18.0f, 18.0f, level);
    EXPECT_LT(glm::length(n - glm::normalize(glm::vec3(g0.x, 1.0f, g0.y))), 1e-6f) << "level " << level;
  }
}

// The raster at its footprint's level against the ray cast at the same: a distant view of fine
// relief agrees better than both at level 0 (the change's point), and the CPU truth computed here
// level by level is raycastImage's.
TEST_F(FilteredShading, RasterAndTruthAgreeBetterThanAtLevelZeroOnADistantView) {
  const Heightfield& hf = detailedTerrain();
  const int w = 320, h = 180;
  // From 2,800 units at 22 degrees the terrain spans two thirds of the frame's width, several
  // samples to a pixel.
  const CameraPose pose = lbtest::poseAt({-1400, 900, -1400}, {500, 0, 500}, 22.0f);
  // Grid 16 at level 32: one vertex per sample, so the two images differ by the surface between
  // samples (triangles against the bilinear patch) and by filtering, nothing coarser.
  auto raster = [&](bool mipZero) {
    RenderSettings s{w, h, 16};
    s.testMipZeroShading = mipZero;
    Renderer r(gpu(), hf, s);
    r.setScheme(*findScheme("uniform"), {{"level", 32}});
    return RgbaImage{w, h, r.renderImage(pose, pose, RenderMode::Shaded)};
  };
  const RgbaImage filtered = raster(false), level0 = raster(true);
  const RgbaImage truth = raycastImage(hf, pose, w, h);
  EXPECT_EQ(truth.px, truthAt(hf, pose, w, h, -1).px);
  const RgbaImage truth0 = truthAt(hf, pose, w, h, 0);
  const double before = compareImages(level0, truth0).psnrDb, after = compareImages(filtered, truth).psnrDb;
  std::printf("raster against ray cast, distant view: PSNR %.2f dB at level 0, %.2f dB filtered\n", before, after);
  EXPECT_GT(after, before + 2.0);  // measured on lavapipe: 43.9 dB at level 0, 48.7 dB filtered
  // Shading alone: the same pixels hold terrain in all four.
  for (size_t i = 0; i < filtered.px.size(); i += 4) {
    ASSERT_EQ(isClear(filtered, int(i / 4 % w), int(i / 4 / w)), isClear(level0, int(i / 4 % w), int(i / 4 / w)));
    ASSERT_EQ(isClear(truth, int(i / 4 % w), int(i / 4 / w)), isClear(truth0, int(i / 4 % w), int(i / 4 / w)));
  }
}

// The filter changes shading only: a scheme of each draw path counts and measures the same as with
// level-0 shading (every scheme's error images are pinned by ImageHashes, its counters by the CI
// baseline).
TEST_F(FilteredShading, CountersAndErrorMapsAreUnchanged) {
  const Heightfield& t = lbtest::testTerrain();
  const CameraPose pose = lbtest::overviewPose();
  for (const char* name : {"sphere", "cdlod", "cbt", "cbt-ts"}) {
    const Scheme* s = findScheme(name);
    SCOPED_TRACE(name);
    auto run = [&](bool mipZero, FrameResult& f, std::vector<float>& error, std::vector<uint8_t>& shaded) {
      RenderSettings rs{64, 36, 4};
      rs.testMipZeroShading = mipZero;
      Renderer r(gpu(), t, rs);
      r.setScheme(*s, {});
      f = lbtest::renderOnce(r, pose);
      error = r.renderErrorMap(pose, pose);
      shaded = r.renderImage(pose, pose, RenderMode::Shaded);
    };
    FrameResult a, b;
    std::vector<float> ea, eb;
    std::vector<uint8_t> sa, sb;
    run(false, a, ea, sa);
    run(true, b, eb, sb);
    EXPECT_EQ(a.stats.iaPrimitives, b.stats.iaPrimitives);
    EXPECT_EQ(a.stats.tesInvocations, b.stats.tesInvocations);
    EXPECT_EQ(a.stats.clipInvocations, b.stats.clipInvocations);
    EXPECT_EQ(a.stats.fsInvocations, b.stats.fsInvocations);
    EXPECT_EQ(a.instances, b.instances);
    EXPECT_EQ(ea, eb);
    EXPECT_EQ(sa.size(), sb.size());
  }
}
