// distance scheme (ch9 Listing 9.7): captured factors equal lerp(min_lod, max_lod, 1 - saturate(
// (d - dmin) / (dmax - dmin))) computed on the CPU from the same patch and edge midpoints, with d,
// dmin and dmax in terrain extents.
#include <algorithm>
#include <cmath>

#include "config/config.h"
#include "error.h"
#include "gpu_fixture.h"
#include "render/patch_grid.h"
#include "shaders/shared.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

constexpr int kGrid = 8;
constexpr double kMinLod = 2, kMaxLod = 40, kDmin = 0.05, kDmax = 0.4;  // extents
const ParamValues kParams = {{"min_lod", kMinLod}, {"max_lod", kMaxLod}, {"dmin", kDmin}, {"dmax", kDmax}};

// Listing 9.7 in double precision.
double listingLod(glm::dvec3 eye, glm::dvec3 p) {
  double s = std::clamp((glm::distance(eye, p) / testTerrain().extent - kDmin) / (kDmax - kDmin), 0.0, 1.0);
  return kMinLod + (kMaxLod - kMinLod) * (1.0 - s);
}

// Displaced grid corners as the vertex shader makes them: (x, height(x, z), z).
glm::dvec3 corner(int i, int j) {
  glm::vec2 xz = gridVertices(kGrid, testTerrain().extent)[size_t(j * (kGrid + 1) + i)];
  return {xz.x, testTerrain().sample(xz.x, xz.y), xz.y};
}

glm::dvec3 patchMid(int i, int j) {
  return (corner(i, j) + corner(i + 1, j) + corner(i + 1, j + 1) + corner(i, j + 1)) * 0.25;
}

void expectNear(double got, double want, const char* what, int i, int j) {
  EXPECT_NEAR(got, want, 1e-4 * std::abs(want)) << what << " of patch (" << i << ", " << j << ")";
}

class DistanceScheme : public lbtest::GpuTest {
 protected:
  // Renders with the eye `height` above patch (pi, pj)'s midpoint, checks every drawn patch against
  // the formula; returns the captured levels.
  std::vector<float> checkFrom(int pi, int pj, float height, int* nearCount, int* farCount) {
    Renderer r(gpu(), testTerrain(), {160, 90, kGrid});
    r.setScheme(*findScheme("distance"), kParams);
    glm::vec3 eye = glm::vec3(patchMid(pi, pj)) + glm::vec3(0, height, 0);
    // Looking down and diagonally across the terrain: the patch below stays in view.
    auto pose = lbtest::poseAt(eye, eye + glm::vec3(200, -height, 200), 90);
    r.renderImage(pose, pose, RenderMode::Shaded);
    auto lv = r.capturedLevels();
    const glm::dvec3 e(eye);
    *nearCount = *farCount = 0;
    for (int j = 0; j < kGrid; ++j)
      for (int i = 0; i < kGrid; ++i) {
        const float* l = &lv[size_t(j * kGrid + i) * LB_CAPTURE_STRIDE];
        if (l[4] == 0.0f) {  // culled: every factor 0
          for (int k = 0; k < 6; ++k) EXPECT_EQ(l[k], 0.0f);
          continue;
        }
        double d = glm::distance(e, patchMid(i, j)) / testTerrain().extent;
        *nearCount += d < kDmin;
        *farCount += d > kDmax;
        double inner = listingLod(e, patchMid(i, j));
        expectNear(l[4], inner, "inner[0]", i, j);
        expectNear(l[5], inner, "inner[1]", i, j);
        // Edges: u=0 (c0-c3), v=0 (c0-c1), u=1 (c1-c2), v=1 (c3-c2), each from its own midpoint.
        glm::dvec3 c0 = corner(i, j), c1 = corner(i + 1, j), c2 = corner(i + 1, j + 1), c3 = corner(i, j + 1);
        expectNear(l[0], listingLod(e, 0.5 * (c0 + c3)), "outer u=0", i, j);
        expectNear(l[1], listingLod(e, 0.5 * (c0 + c1)), "outer v=0", i, j);
        expectNear(l[2], listingLod(e, 0.5 * (c1 + c2)), "outer u=1", i, j);
        expectNear(l[3], listingLod(e, 0.5 * (c3 + c2)), "outer v=1", i, j);
      }
    return lv;
  }
};

}  // namespace

TEST_F(DistanceScheme, NearerThanDminIsMaxLodFartherThanDmaxIsMinLod) {
  int nearCount, farCount;
  // 30 units above patch (2,2)'s midpoint: d = 0.03 extents < dmin there.
  auto lv = checkFrom(2, 2, 30.0f, &nearCount, &farCount);
  const float* p = &lv[size_t(2 * kGrid + 2) * LB_CAPTURE_STRIDE];
  EXPECT_FLOAT_EQ(p[4], float(kMaxLod));
  EXPECT_GE(nearCount, 1);
  EXPECT_GE(farCount, 5);  // the far corner of the 1000-unit terrain is > 1000 away
  for (size_t k = 0; k < lv.size(); k += LB_CAPTURE_STRIDE)
    if (lv[k + 4] > 0) {
      EXPECT_GE(lv[k + 4], float(kMinLod));
      EXPECT_LE(lv[k + 4], float(kMaxLod));
    }
}

TEST_F(DistanceScheme, HalfwayBetweenDminAndDmaxIsMidLevel) {
  int nearCount, farCount;
  // d = (dmin + dmax) / 2 -> saturate term 0.5 -> level (min_lod + max_lod) / 2 = 21.
  auto lv = checkFrom(3, 1, float(0.5 * (kDmin + kDmax) * testTerrain().extent), &nearCount, &farCount);
  EXPECT_NEAR(lv[size_t(1 * kGrid + 3) * LB_CAPTURE_STRIDE + 4], 0.5 * (kMinLod + kMaxLod), 1e-4 * 21);
  EXPECT_EQ(nearCount, 0);
}

TEST_F(DistanceScheme, SharedEdgesGetIdenticalLevels) {
  Renderer r(gpu(), testTerrain(), {160, 90, 16});
  r.setScheme(*findScheme("distance"), {{"dmin", 0.05}, {"dmax", 2}});  // most patches between the two
  auto pose = lbtest::poseAt({-100, 250, -100}, {500, 0, 500});
  r.renderImage(pose, pose, RenderMode::Shaded);
  auto lv = r.capturedLevels();
  const int n = 16;
  int compared = 0, differing = 0;  // differing: the two patches' own (inner) LODs differ
  auto check = [&](const float* p, const float* q, int pEdge, int qEdge) {
    if (p[4] == 0 || q[4] == 0) return;  // a culled neighbour draws nothing
    EXPECT_EQ(p[pEdge], q[qEdge]);
    ++compared;
    differing += p[4] != q[4];
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float* p = &lv[size_t(j * n + i) * LB_CAPTURE_STRIDE];
      if (i + 1 < n) check(p, &lv[size_t(j * n + i + 1) * LB_CAPTURE_STRIDE], 2, 0);    // u=1 | u=0
      if (j + 1 < n) check(p, &lv[size_t((j + 1) * n + i) * LB_CAPTURE_STRIDE], 3, 1);  // v=1 | v=0
    }
  EXPECT_GT(compared, 50);
  EXPECT_GT(differing, 50);
}

TEST_F(DistanceScheme, RejectsInvertedRanges) {
  Renderer r(gpu(), testTerrain(), {64, 64, 2});
  const Scheme& s = *findScheme("distance");
  EXPECT_THROW(r.setScheme(s, {{"dmin", 0.5}, {"dmax", 0.5}}), InputError);
  EXPECT_THROW(r.setScheme(s, {{"dmin", 0.6}, {"dmax", 0.1}}), InputError);
  // World-unit distances of the former parameters are out of range, not silently saturated.
  EXPECT_THROW(r.setScheme(s, {{"dmin", 50}, {"dmax", 1000}}), InputError);
  EXPECT_THROW(r.setScheme(s, {{"min_lod", 20}, {"max_lod", 10}}), InputError);
  EXPECT_THROW(r.setScheme(s, {{"max_lod", 65}}), InputError);
  try {
    s.validate(resolveParams(s.info(), {{"dmin", 0.5}, {"dmax", 0.1}}));
    ADD_FAILURE() << "dmax < dmin accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dmax"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(r.setScheme(s, {{"dmin", 0}, {"dmax", 1}}));
}

// Config files reach the same cross-parameter check, naming the scheme's params object.
TEST(DistanceConfig, InvertedRangeInAConfigIsAnInputError) {
  const std::string text = R"({"name": "t", "paths": ["paths/flyover.csv"],
    "schemes": [{"name": "distance", "params": {"dmin": [0.1, 0.9], "dmax": 0.8}}]})";
  try {
    parseConfig(text, "t.json", LODBENCH_SOURCE_DIR "/configs");
    ADD_FAILURE() << "dmin 0.9 > dmax 0.8 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/schemes/0/params"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("dmax"), std::string::npos) << e.what();
  }
}
