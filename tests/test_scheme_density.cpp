// Density scheme: the density map on synthetic heightfields (exact values by hand from the seed's
// formula), the edge walk, and on the GPU the edge factors = sphere factors x max density along the edge.
#include <algorithm>
#include <cmath>

#include "gpu_fixture.h"
#include "schemes/preprocess/density_map.h"

using namespace lb;

namespace {

// w x h heightfield from f(x, z), with its range filled in.
template <class F>
Heightfield field(int w, int h, F f) {
  Heightfield hf;
  hf.width = w;
  hf.height = h;
  for (int z = 0; z < h; ++z)
    for (int x = 0; x < w; ++x) hf.h.push_back(f(x, z));
  hf.updateRange();
  return hf;
}

}  // namespace

TEST(DensityMap, TiltedPlaneIsEverywhereTheMinimum) {
  // h = x + 3z on 5 x 5: range 16, so normalised heights are exact and every second difference is 0.
  Heightfield plane = field(5, 5, [](int x, int z) { return float(x + 3 * z); });
  for (float threshold : {0.0f, 0.01f})
    for (float scale : {1.0f, 40.0f, 10000.0f}) {
      auto d = densityMap(plane, threshold, scale);
      ASSERT_EQ(d.size(), 25u);
      for (float v : d) EXPECT_EQ(v, kMinDensity) << "threshold " << threshold << " scale " << scale;
    }
}

TEST(DensityMap, RidgeValuesFollowTheSeedFormula) {
  // A ridge along x at z = 2: height 4 there, 0 elsewhere; normalised by the range 4 -> 1 and 0.
  Heightfield ridge = field(5, 5, [](int, int z) { return z == 2 ? 4.0f : 0.0f; });
  auto at = [](const std::vector<float>& d, int x, int z) { return d[size_t(z) * 5 + size_t(x)]; };
  // On the ridge: along x |(1-1)-(1-1)| = 0; along z and both diagonals |(0-1)-(1-0)| = 2.
  const float onRidge = 0.293f * 2 + 0.207f * 2 + 0.207f * 2;  // 1.414
  // Beside it (z = 1 or 3): along x 0; along z and both diagonals |(1-0)-(0-0)| = 1 (one end on the ridge).
  const float beside = 0.293f * 1 + 0.207f * 1 + 0.207f * 1;  // 0.707
  auto d = densityMap(ridge, 0.0f, 0.25f);
  for (int x = 0; x < 5; ++x) {  // border columns copy the nearest interior sample
    EXPECT_NEAR(at(d, x, 2), 0.25f * onRidge, 1e-6f) << x;
    EXPECT_NEAR(at(d, x, 1), 0.25f * beside, 1e-6f) << x;
    EXPECT_NEAR(at(d, x, 3), 0.25f * beside, 1e-6f) << x;
    EXPECT_EQ(at(d, x, 0), at(d, x, 1)) << "border row copies its interior neighbour";
    EXPECT_EQ(at(d, x, 4), at(d, x, 3));
  }
  EXPECT_GT(at(d, 2, 2), kMinDensity);
  // Threshold: a variation counts when it is >= threshold. 1.5 drops the 1s beside the ridge, not the 2s.
  d = densityMap(ridge, 1.5f, 0.25f);
  EXPECT_NEAR(at(d, 2, 2), 0.25f * onRidge, 1e-6f);
  EXPECT_EQ(at(d, 2, 1), kMinDensity);
  EXPECT_NEAR(densityMap(ridge, 2.0f, 0.25f)[2 * 5 + 2], 0.25f * onRidge, 1e-6f);
  EXPECT_EQ(densityMap(ridge, 2.001f, 0.25f)[2 * 5 + 2], kMinDensity);
  // Clamp: scale 1 gives 1.414 on the ridge -> 1, 0.707 beside it; scale 0 gives the minimum.
  d = densityMap(ridge, 0.0f, 1.0f);
  EXPECT_EQ(at(d, 2, 2), 1.0f);
  EXPECT_NEAR(at(d, 2, 1), beside, 1e-6f);
  for (float v : densityMap(ridge, 0.0f, 0.0f)) EXPECT_EQ(v, kMinDensity);
}

TEST(DensityMap, EdgeWalkVisitsTheSameTexelsEitherWay) {
  // 9 x 3 map, zero except one texel per probe; the walk must see it only when it lies on the edge.
  std::vector<float> map(27, 0.0f);
  auto one = [&](int x, int z) {
    std::fill(map.begin(), map.end(), 0.0f);
    map[size_t(z) * 9 + size_t(x)] = 1.0f;
  };
  one(4, 1);
  EXPECT_EQ(maxDensityAlongEdge(map, 9, {0, 1}, {8, 1}), 1.0f);  // horizontal through it
  EXPECT_EQ(maxDensityAlongEdge(map, 9, {8, 1}, {0, 1}), 1.0f);
  EXPECT_EQ(maxDensityAlongEdge(map, 9, {0, 0}, {8, 0}), 0.0f);  // the row above misses it
  EXPECT_EQ(maxDensityAlongEdge(map, 9, {4, 0}, {4, 2}), 1.0f);  // vertical
  // Diagonal (0,0)-(8,2): 9 texels, z = round(k / 4) = 0,0,1,1,1,1,2,2,2 (halves away from 0) -> (2,1)..(5,1).
  for (int x = 0; x < 9; ++x) {
    one(x, 1);
    float expected = (x >= 2 && x <= 5) ? 1.0f : 0.0f;
    EXPECT_EQ(maxDensityAlongEdge(map, 9, {0, 0}, {8, 2}), expected) << x;
    EXPECT_EQ(maxDensityAlongEdge(map, 9, {8, 2}, {0, 0}), expected) << x << " reversed";
  }
  // Grid vertex -> texel: round(i * (size - 1) / n).
  EXPECT_EQ(gridTexel(0, 16, 129), 0);
  EXPECT_EQ(gridTexel(1, 16, 129), 8);
  EXPECT_EQ(gridTexel(16, 16, 129), 128);
  EXPECT_EQ(gridTexel(1, 3, 9), 3);   // 8/3 = 2.67 -> 3
  EXPECT_EQ(gridTexel(1, 16, 9), 1);  // 0.5 -> 1 (half up)
  EXPECT_EQ(gridTexel(1, 5, 9), 2);   // 1.6 -> 2
}

class DensityScheme : public lbtest::GpuTest {};

// Every edge factor is the sphere scheme's factor for that edge times the maximum density along the
// edge, clamped to [1, 64]; culled patches match too. Edges where the sphere factor saturates at 64
// are not comparable (the product of the unclamped factor may still be below 64) and must not occur.
TEST_F(DensityScheme, EdgeFactorsAreSphereFactorsTimesMaxDensity) {
  const int n = 16;
  const float triSize = 1.5f, scale = 8.0f;
  const Heightfield& hf = lbtest::testTerrain();
  Renderer r(lbtest::gpu(), hf, {160, 90, n});
  auto pose = lbtest::poseAt({-150, 350, -150}, {500, 0, 500}, 40);
  r.setScheme(*findScheme("sphere"), {{"tri_size", triSize}});
  r.renderImage(pose, pose, RenderMode::Shaded);
  auto sphere = r.capturedLevels();
  r.setScheme(*findScheme("density"), {{"tri_size", triSize}, {"scale", scale}, {"threshold", 0}});
  r.renderImage(pose, pose, RenderMode::Shaded);
  auto density = r.capturedLevels();
  auto map = densityMap(hf, 0.0f, scale);
  auto texel = [&](int i, int j) { return glm::ivec2(gridTexel(i, n, hf.width), gridTexel(j, n, hf.height)); };
  int compared = 0, reduced = 0, culled = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float* s = &sphere[size_t(j * n + i) * 8];
      const float* d = &density[size_t(j * n + i) * 8];
      if (s[4] == 0.0f) {
        ++culled;
        for (int k = 0; k < 6; ++k) EXPECT_EQ(d[k], 0.0f) << "culled patch " << i << "," << j;
        continue;
      }
      // Edges in Vulkan quad order: c0-c3, c0-c1, c1-c2, c3-c2.
      const glm::ivec2 c0 = texel(i, j), c1 = texel(i + 1, j), c2 = texel(i + 1, j + 1), c3 = texel(i, j + 1);
      const glm::ivec2 ends[4][2] = {{c0, c3}, {c0, c1}, {c1, c2}, {c3, c2}};
      for (int e = 0; e < 4; ++e) {
        ASSERT_LT(s[e], 64.0f) << "pick a camera where no sphere factor saturates";
        float expected = std::clamp(s[e] * maxDensityAlongEdge(map, hf.width, ends[e][0], ends[e][1]), 1.0f, 64.0f);
        EXPECT_NEAR(d[e], expected, 1e-4f) << "patch " << i << "," << j << " edge " << e;
        reduced += d[e] < s[e] - 0.5f;
        ++compared;
      }
      EXPECT_EQ(d[4], std::max(d[1], d[3]));
      EXPECT_EQ(d[5], std::max(d[0], d[2]));
    }
  EXPECT_GT(compared, 400);
  EXPECT_GT(culled, 0) << "the view should leave some patches outside the frustum";
  EXPECT_GT(reduced, compared / 4) << "density should lower many factors";
}

// Neighbours compute the shared edge's density independently; they must agree bit for bit.
TEST_F(DensityScheme, SharedEdgesGetIdenticalLevels) {
  const int n = 16;
  Renderer r(lbtest::gpu(), lbtest::testTerrain(), {160, 90, n});
  r.setScheme(*findScheme("density"), {{"scale", 8}});
  auto pose = lbtest::poseAt({-100, 250, -100}, {500, 0, 500});
  r.renderImage(pose, pose, RenderMode::Shaded);
  auto lv = r.capturedLevels();
  int compared = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float* p = &lv[size_t(j * n + i) * 8];
      if (p[4] == 0) continue;
      if (i + 1 < n && lv[size_t(j * n + i + 1) * 8 + 4] > 0) {
        EXPECT_EQ(p[2], lv[size_t(j * n + i + 1) * 8 + 0]);
        ++compared;
      }
      if (j + 1 < n && lv[size_t((j + 1) * n + i) * 8 + 4] > 0) {
        EXPECT_EQ(p[3], lv[size_t((j + 1) * n + i) * 8 + 1]);
        ++compared;
      }
    }
  EXPECT_GT(compared, 50);
}
