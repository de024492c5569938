// planefit scheme (ch9 9.1.2, Listings 9.10-9.16): the compute pass equals the CPU reference, both
// fits behave as derived on planar heightfields, and the control shader's factors equal the
// weighted distance LOD computed on the CPU from the lookup texture.
#include <algorithm>
#include <cmath>

#include "error.h"
#include "gpu_fixture.h"
#include "render/patch_grid.h"
#include "schemes/preprocess/plane_fit.h"
#include "shaders/shared.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

bool close(double got, double want) {
  return std::abs(got - want) <= 1e-4 * std::max(1.0, std::abs(want));
}

// 128^2 samples (a multiple of 16: no clamped blocks) over extent 1000; h(x, z) in world units.
template <class F>
Heightfield planarField(F height) {
  Heightfield hf;
  hf.width = hf.height = 128;
  hf.extent = 1000;
  const float spacing = hf.extent / 127.0f;
  for (int z = 0; z < 128; ++z)
    for (int x = 0; x < 128; ++x) hf.h.push_back(height(float(x) * spacing, float(z) * spacing, x));
  hf.updateRange();
  return hf;
}

// Runs the compute pass for `fit` on `hf`, checks it against the CPU reference, returns it.
PlaneFitResult gpuMatchesCpu(const Heightfield& hf, PlaneFit fit) {
  Renderer r(gpu(), hf, {64, 64, 4});
  r.setScheme(*findScheme("planefit"), {{"fit", double(fit)}});
  SchemeTexture tex = r.readSchemeTexture();
  PlaneFitResult cpu = fitPlanes(hf, fit);
  EXPECT_EQ(tex.width, cpu.width);
  EXPECT_EQ(tex.height, cpu.height);
  for (int bz = 0; bz < std::min(tex.height, cpu.height); ++bz)
    for (int bx = 0; bx < std::min(tex.width, cpu.width); ++bx) {
      const float* g = &tex.rgba[size_t(bz * tex.width + bx) * 4];
      const PlaneFitBlock& c = cpu.at(bx, bz);
      for (int k = 0; k < 3; ++k)
        EXPECT_PRED2(close, g[k], c.normal[k]) << "normal[" << k << "] of block " << bx << "," << bz;
      EXPECT_PRED2(close, g[3], c.deviation) << "deviation of block " << bx << "," << bz;
    }
  return cpu;
}

class PlaneFitScheme : public lbtest::GpuTest {};

}  // namespace

TEST_F(PlaneFitScheme, ComputePassEqualsCpuReferenceBook) {
  auto cpu = gpuMatchesCpu(testTerrain(), PlaneFit::Book);
  EXPECT_EQ(cpu.width, 9);  // 129 samples: 8 full blocks + one of clamped border samples
}

TEST_F(PlaneFitScheme, ComputePassEqualsCpuReferenceLeastSquares) {
  gpuMatchesCpu(testTerrain(), PlaneFit::LeastSquares);
}

TEST_F(PlaneFitScheme, LeastSquaresRecoversATiltedPlaneExactly) {
  const double b = 0.3, c = -0.1;
  Heightfield hf = planarField([&](float x, float z, int) { return float(200 + b * x + c * z); });
  auto fit = gpuMatchesCpu(hf, PlaneFit::LeastSquares);
  const glm::dvec3 want = glm::normalize(glm::dvec3(-b, 1, -c));
  for (const PlaneFitBlock& blk : fit.blocks) {
    EXPECT_LT(blk.deviation, 1e-3);  // float residuals of heights up to 300
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(blk.normal[k], want[k], 1e-5);
  }
}

TEST_F(PlaneFitScheme, BookFitIsExactOnFlatGroundButNotOnASlope) {
  Heightfield flat = planarField([](float, float, int) { return 42.0f; });
  for (const PlaneFitBlock& blk : gpuMatchesCpu(flat, PlaneFit::Book).blocks) {
    EXPECT_EQ(blk.deviation, 0.0f);
    EXPECT_EQ(blk.normal, glm::vec3(0, 1, 0));
  }
  // h = 2 * sample index along x: normalized heights step 1/127 per sample. The corners sit 1/64
  // apart but the samples 1/15 apart (Listings 9.12, 9.15), so the corner plane has slope 64 * 15/127
  // / 15 per unit while the samples rise 15/127 per unit: every sample (gx, gy) lies
  // 63 gx / (127 L) off the plane, L = |(-64 * 15/127, 1, 0)|, and the deviation is
  // (63 / (127 L)) sqrt(16 * sum_{gx<16} gx^2 / 255), sum gx^2 = 1240.
  Heightfield slope = planarField([](float, float, int x) { return 2.0f * float(x); });
  const double l = std::sqrt(1.0 + std::pow(64.0 * 15.0 / 127.0, 2));
  const double want = 63.0 / (127.0 * l) * std::sqrt(16.0 * 1240.0 / 255.0);
  for (const PlaneFitBlock& blk : gpuMatchesCpu(slope, PlaneFit::Book).blocks) {
    EXPECT_NEAR(blk.deviation, want, 1e-4 * want);
    EXPECT_NEAR(blk.normal.x, -64.0 * 15.0 / 127.0 / l, 1e-5);
    EXPECT_NEAR(blk.normal.y, 1.0 / l, 1e-5);
  }
  // The corrected fit sees the same slope as a plane.
  for (const PlaneFitBlock& blk : fitPlanes(slope, PlaneFit::LeastSquares).blocks) EXPECT_LT(blk.deviation, 1e-3);
}

namespace {

// planefit.tesc's blockSpan(): blocks along one axis for grid coordinates [g0, g1].
std::pair<int, int> blockSpan(int g0, int g1, int samples, int blocks, int n) {
  const int d = n * LB_PLANE_FIT_BLOCK, a0 = g0 * (samples - 1), a1 = g1 * (samples - 1);
  int lo = g0 == g1 ? (a0 + d - 1) / d - 1 : a0 / d;
  int hi = g0 == g1 ? a1 / d : (a1 + d - 1) / d - 1;
  return {std::clamp(lo, 0, blocks - 1), std::clamp(hi, 0, blocks - 1)};
}

}  // namespace

class PlaneFitLevels : public lbtest::GpuTest, public ::testing::WithParamInterface<int> {};

// Every drawn patch: level = lerp(min_lod, max_lod, (1 - saturate((d - dmin) / (dmax - dmin))) *
// saturate(max block deviation / (roughness x extent))) at the patch and edge midpoints (d, dmin,
// dmax in extents; the lsq deviation in world units); shared edges agree.
TEST_P(PlaneFitLevels, FactorsAreWeightedDistanceLod) {
  const int n = GetParam();  // 8: patches aligned with the 16-sample blocks; 6: not aligned
  // roughness above every block deviation of the test terrain (max 16.5 world units of 1000): every weight < 1.
  const double minLod = 2, maxLod = 40, dmin = 0.05, dmax = 0.9, roughness = 0.02;
  const double extent = testTerrain().extent;
  Renderer r(gpu(), testTerrain(), {160, 90, n});
  r.setScheme(
      *findScheme("planefit"),
      {{"min_lod", minLod}, {"max_lod", maxLod}, {"dmin", dmin}, {"dmax", dmax}, {"fit", 1}, {"roughness", roughness}});
  SchemeTexture tex = r.readSchemeTexture();
  const glm::vec3 eye(150, 180, 120);
  auto pose = lbtest::poseAt(eye, {700, 0, 800}, 80);
  r.renderImage(pose, pose, RenderMode::Shaded);
  auto lv = r.capturedLevels();

  const Heightfield& hf = testTerrain();
  auto grid = gridVertices(n, hf.extent);
  auto corner = [&](int i, int j) {
    glm::vec2 xz = grid[size_t(j * (n + 1) + i)];
    return glm::dvec3(xz.x, hf.sample(xz.x, xz.y), xz.y);
  };
  auto level = [&](glm::dvec3 p, glm::ivec2 g0, glm::ivec2 g1) {
    auto bx = blockSpan(g0.x, g1.x, hf.width, tex.width, n), bz = blockSpan(g0.y, g1.y, hf.height, tex.height, n);
    double dev = 0;
    for (int z = bz.first; z <= bz.second; ++z)
      for (int x = bx.first; x <= bx.second; ++x)
        dev = std::max(dev, double(tex.rgba[size_t(z * tex.width + x) * 4 + 3]));
    double s = std::clamp((glm::distance(glm::dvec3(eye), p) / extent - dmin) / (dmax - dmin), 0.0, 1.0);
    return minLod + (maxLod - minLod) * (1 - s) * std::clamp(dev / (roughness * extent), 0.0, 1.0);
  };
  int drawn = 0, belowDistanceLod = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float* l = &lv[size_t(j * n + i) * LB_CAPTURE_STRIDE];
      if (l[4] == 0) continue;
      ++drawn;
      glm::ivec2 c(i, j);
      glm::dvec3 c0 = corner(i, j), c1 = corner(i + 1, j), c2 = corner(i + 1, j + 1), c3 = corner(i, j + 1);
      double inner = level((c0 + c1 + c2 + c3) * 0.25, c, c + 1);
      EXPECT_NEAR(l[4], inner, 1e-4 * inner) << "inner of patch " << i << "," << j;
      EXPECT_EQ(l[4], l[5]);
      EXPECT_NEAR(l[0], level(0.5 * (c0 + c3), c, c + glm::ivec2(0, 1)), 1e-4 * inner) << i << "," << j;
      EXPECT_NEAR(l[1], level(0.5 * (c0 + c1), c, c + glm::ivec2(1, 0)), 1e-4 * inner) << i << "," << j;
      EXPECT_NEAR(l[2], level(0.5 * (c1 + c2), c + glm::ivec2(1, 0), c + 1), 1e-4 * inner) << i << "," << j;
      EXPECT_NEAR(l[3], level(0.5 * (c3 + c2), c + glm::ivec2(0, 1), c + 1), 1e-4 * inner) << i << "," << j;
      double s = std::clamp(
          (glm::distance(glm::dvec3(eye), (c0 + c1 + c2 + c3) * 0.25) / extent - dmin) / (dmax - dmin), 0., 1.);
      belowDistanceLod += inner < minLod + (maxLod - minLod) * (1 - s) - 1e-3;  // the weight lowered it
      if (i + 1 < n && lv[size_t(j * n + i + 1) * LB_CAPTURE_STRIDE + 4] > 0) {
        EXPECT_EQ(l[2], lv[size_t(j * n + i + 1) * LB_CAPTURE_STRIDE + 0]) << "crack at u=1 of " << i << "," << j;
      }
      if (j + 1 < n && lv[size_t((j + 1) * n + i) * LB_CAPTURE_STRIDE + 4] > 0) {
        EXPECT_EQ(l[3], lv[size_t((j + 1) * n + i) * LB_CAPTURE_STRIDE + 1]) << "crack at v=1 of " << i << "," << j;
      }
    }
  EXPECT_GE(drawn, n * n / 2);
  EXPECT_GE(belowDistanceLod, drawn / 4);
}
INSTANTIATE_TEST_SUITE_P(Grids, PlaneFitLevels, ::testing::Values(8, 6));

TEST_F(PlaneFitScheme, FlatTerrainGetsMinLodEvenUpClose) {
  Heightfield flat = planarField([](float, float, int) { return 10.0f; });
  for (double fit : {0.0, 1.0}) {
    Renderer r(gpu(), flat, {64, 64, 4});
    r.setScheme(*findScheme("planefit"), {{"fit", fit}, {"min_lod", 3}, {"max_lod", 30}});
    auto pose = lbtest::poseAt({500, 40, 500}, {900, 0, 900}, 90);  // 30 above the ground: d < dmin
    r.renderImage(pose, pose, RenderMode::Shaded);
    auto lv = r.capturedLevels();
    int drawn = 0;
    for (uint32_t p = 0; p < r.patchCount(); ++p) {
      if (lv[p * LB_CAPTURE_STRIDE + 4] == 0) continue;
      ++drawn;
      for (int k = 0; k < 6; ++k) EXPECT_EQ(lv[p * LB_CAPTURE_STRIDE + k], 3.0f) << "fit " << fit << " patch " << p;
    }
    EXPECT_GT(drawn, 0);
  }
}

TEST_F(PlaneFitScheme, RejectsInvertedDistanceRange) {
  Renderer r(gpu(), testTerrain(), {64, 64, 2});
  EXPECT_THROW(r.setScheme(*findScheme("planefit"), {{"dmin", 0.3}, {"dmax", 0.2}}), InputError);
  EXPECT_THROW(r.setScheme(*findScheme("planefit"), {{"fit", 0.5}}), InputError);
  EXPECT_THROW(r.setScheme(*findScheme("planefit"), {{"fit", 2}}), InputError);
}
