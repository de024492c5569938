// The surplus oracle: smallest uniform level per patch meeting a screen-space error bound.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "camera/camera_path.h"
#include "gpu_fixture.h"
#include "metrics/oracle.h"
#include "render/renderer.h"
#include "terrain/heightfield.h"

using namespace lb;

namespace {

template <class F>
Heightfield makeField(int size, float extent, F height) {
  Heightfield hf;
  hf.width = hf.height = size;
  hf.extent = extent;
  hf.h.resize(size_t(size) * size_t(size));
  for (int z = 0; z < size; ++z)
    for (int x = 0; x < size; ++x)
      hf.h[size_t(z) * size_t(size) + size_t(x)] =
          height(extent * float(x) / float(size - 1), extent * float(z) / float(size - 1));
  hf.updateRange();
  return hf;
}

CameraMatrices overview(float extent, int w, int h) {
  return cameraMatrices(
      lbtest::poseAt({-0.2f * extent, 0.6f * extent, -0.2f * extent}, {0.5f * extent, 0, 0.5f * extent}),
      float(w) / float(h), extent);
}

}  // namespace

TEST(Oracle, FlatTerrainNeedsLevelOneEverywhere) {
  Heightfield flat = makeField(65, 1000, [](float, float) { return 10.0f; });
  for (double bound : {0.0, 0.5}) {
    OracleResult r = surplusOracle(flat, 8, overview(1000, 320, 180), 320, 180, bound);
    EXPECT_GT(r.patches, 0);
    EXPECT_EQ(r.saturated, 0);
    EXPECT_EQ(r.triangles, 2u * uint64_t(r.patches));
    for (int level : r.levels) EXPECT_TRUE(level == 0 || level == 1) << level;
  }
}

TEST(Oracle, SingleBumpRaisesOnlyItsPatch) {
  // Raised cosine of radius 50 centred in patch (2, 2) of an 8 x 8 grid (patches 125 wide):
  // exactly zero outside it, so every other patch is flat.
  const float cx = 312.5f, cz = 312.5f, radius = 50;
  Heightfield bump = makeField(129, 1000, [&](float x, float z) {
    float r = std::hypot(x - cx, z - cz);
    return r < radius ? 40.0f * (0.5f + 0.5f * std::cos(3.14159265f * r / radius)) : 0.0f;
  });
  OracleResult r = surplusOracle(bump, 8, overview(1000, 320, 180), 320, 180, 0.5);
  const size_t bumpPatch = 2 * 8 + 2;
  EXPECT_GT(r.levels[bumpPatch], 1);
  for (size_t p = 0; p < r.levels.size(); ++p) {
    if (p == bumpPatch) continue;
    EXPECT_LE(r.levels[p], 1) << "patch " << p;
  }
}

TEST(Oracle, TighterBoundNeverNeedsFewerTriangles) {
  const Heightfield& hf = lbtest::testTerrain();
  CameraMatrices cam = overview(hf.extent, 320, 180);
  OracleResult prev = surplusOracle(hf, 16, cam, 320, 180, 8.0);
  const uint64_t loosest = prev.triangles;
  for (double bound : {4.0, 2.0, 1.0, 0.5}) {
    OracleResult r = surplusOracle(hf, 16, cam, 320, 180, bound);
    EXPECT_GE(r.triangles, prev.triangles) << bound;
    // The exact minimum per patch: the set of levels meeting a tighter bound is a subset.
    for (size_t p = 0; p < r.levels.size(); ++p) EXPECT_GE(r.levels[p], prev.levels[p]) << bound;
    EXPECT_EQ(r.patches, prev.patches) << "culling does not depend on the bound";
    prev = r;
  }
  EXPECT_GT(prev.triangles, 4 * loosest) << "a 16x tighter bound needs far more triangles";
}

// h = a x^2 along x only. Piecewise-linear interpolation over a segment of length d errs by
// a s (d - s) at offset s, at most a d^2 / 4 at the midpoint; this does not depend on where the
// segment is, so every patch needs the same level. An orthographic camera looking along +z maps
// world height to screen y at a constant 600 px / 1200 units = 0.5 px per unit, so with patches
// 256 wide and d = 256 / L the error is 0.5 a (256 / L)^2 / 4 = 8.192 / L^2 px for a = 1e-3.
// (Samples sit on integer x; where no sample hits a midpoint the error is lower by at most
// 0.5 a 0.5^2 = 1.25e-4 px, far from every bound below.)
TEST(Oracle, ParabolaUnderOrthographicCameraNeedsTheDerivedLevel) {
  const float a = 1e-3f;
  Heightfield hf = makeField(1025, 1024, [&](float x, float) { return a * x * x; });
  CameraMatrices cam;
  cam.eye = glm::vec3(512, 500, -10);
  cam.view = glm::lookAt(cam.eye, glm::vec3(512, 500, 0), glm::vec3(0, 1, 0));
  cam.proj = glm::ortho(-512.0f, 512.0f, -600.0f, 600.0f, 0.0f, 2000.0f);
  cam.proj[1][1] *= -1.0f;
  struct Case {
    double bound;
    int level;
  };
  // L = ceil(sqrt(8.192 / bound)): 8.192 / 2^2 = 2.05 > 1 >= 0.91 = 8.192 / 3^2; 0.328 > 0.3 >= 0.228;
  // 0.1011 > 0.1 >= 0.0819; 0.01045 > 0.01 >= 0.00974; and 8.192 / 64^2 = 0.002 > 0.001: saturated.
  for (Case c : {Case{1.0, 3}, Case{0.3, 6}, Case{0.1, 10}, Case{0.01, 29}, Case{0.001, 64}}) {
    OracleResult r = surplusOracle(hf, 4, cam, 1024, 600, c.bound);
    EXPECT_EQ(r.patches, 16);
    EXPECT_EQ(r.saturated, c.level == 64 ? 16 : 0) << c.bound;
    for (int level : r.levels) EXPECT_EQ(level, c.level) << c.bound;
    EXPECT_EQ(r.triangles, 16u * 2u * uint64_t(c.level * c.level)) << c.bound;
  }
}

TEST(Oracle, PatchesOutsideTheFrustumAreCulled) {
  // Looking away from the terrain from its -z border: nothing is drawn.
  const Heightfield& hf = lbtest::testTerrain();
  CameraMatrices cam = cameraMatrices(lbtest::poseAt({500, 200, -10}, {500, 200, -1000}), 16.0f / 9.0f, hf.extent);
  OracleResult r = surplusOracle(hf, 16, cam, 320, 180, 1.0);
  EXPECT_EQ(r.patches, 0);
  EXPECT_EQ(r.triangles, 0u);
  for (int level : r.levels) EXPECT_EQ(level, 0);
}
