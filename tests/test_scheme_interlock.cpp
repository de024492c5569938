// interlock (practical-d3d11-ch9 9.1.1): inner = own midpoint LOD, every edge = min(own, neighbour),
// bit-identical on both sides of every shared edge, and each neighbour's LOD lands on the Vulkan
// outer level of the edge that faces it.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu_fixture.h"
#include "render/draw_limits.h"
#include "render/patch_grid.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

constexpr int kStride = 8;  // LB_CAPTURE_STRIDE: outer[0..3], inner[0..1]
// Neighbour (di, dj) across each Vulkan outer level: u=0, v=0, u=1, v=1 (c0 = (i,j), u along x).
constexpr int kSideDi[4] = {-1, 0, 1, 0};
constexpr int kSideDj[4] = {0, -1, 0, 1};
constexpr int kOpposite[4] = {2, 3, 0, 1};

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

// World-space grid point as the vertex shader displaces it (Heightfield::sample == terrainHeight).
glm::dvec3 gridPoint(int i, int j, int n) {
  const Heightfield& hf = testTerrain();
  i = std::clamp(i, 0, n);
  j = std::clamp(j, 0, n);
  float x = hf.extent * float(i) / float(n), z = hf.extent * float(j) / float(n);
  return {x, hf.sample(x, z), z};
}

// Midpoint of the (clamped) cell (ci, cj): at the border it collapses onto the shared edge (Listing 9.2).
glm::dvec3 cellMidpoint(int ci, int cj, int n) {
  return (gridPoint(ci, cj, n) + gridPoint(ci + 1, cj, n) + gridPoint(ci + 1, cj + 1, n) + gridPoint(ci, cj + 1, n)) /
         4.0;
}

struct LodParams {  // distances in terrain extents, as the scheme's dmin and dmax
  double minDistance = 0.1, maxDistance = 1.5, minLod = 1, maxLod = 16;
};

// Listing 9.7 in double precision: the reference the GPU's float result must be close to.
double referenceLod(const glm::dvec3& mid, const glm::vec3& eye, const LodParams& p) {
  double d = glm::distance(mid, glm::dvec3(eye)) / testTerrain().extent;
  double s = std::clamp((d - p.minDistance) / (p.maxDistance - p.minDistance), 0.0, 1.0);
  return p.minLod + (1.0 - s) * (p.maxLod - p.minLod);
}

std::vector<float> captureLevels(Renderer& r, const CameraPose& pose) {
  r.renderImage(pose, pose, RenderMode::Shaded);
  return r.capturedLevels();
}

// Checks every interlocking-tile rule on one captured frame; returns the number of shared edges compared.
int checkInterlocked(const std::vector<float>& lv, int n, const CameraPose& pose, const LodParams& p,
                     const std::string& where) {
  int compared = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const float* a = &lv[size_t(j * n + i) * kStride];
      if (a[4] == 0.0f) {  // culled: all six levels are 0
        for (int k = 0; k < 6; ++k) EXPECT_EQ(a[k], 0.0f) << where << " patch " << i << "," << j;
        continue;
      }
      const std::string at = where + " patch " + std::to_string(i) + "," + std::to_string(j);
      EXPECT_EQ(bits(a[4]), bits(a[5])) << at << ": both inner levels are the own LOD";
      EXPECT_NEAR(a[4], referenceLod(cellMidpoint(i, j, n), pose.eye, p), 1e-3) << at;
      for (int k = 0; k < 6; ++k) {
        EXPECT_GE(a[k], 1.0f) << at << " level " << k;
        EXPECT_LE(a[k], 64.0f) << at << " level " << k;
      }
      for (int k = 0; k < 4; ++k) {
        int ni = i + kSideDi[k], nj = j + kSideDj[k];
        if (ni < 0 || nj < 0 || ni >= n || nj >= n) {
          // Border: the clamped neighbour is the edge midpoint; its LOD is not any patch's inner.
          double edgeLod = referenceLod(cellMidpoint(ni, nj, n), pose.eye, p);
          EXPECT_NEAR(a[k], std::min(double(a[4]), edgeLod), 1e-3) << at << " border edge " << k;
          EXPECT_LE(a[k], a[4]) << at << " border edge " << k;
          continue;
        }
        const float* b = &lv[size_t(nj * n + ni) * kStride];
        if (b[4] == 0.0f) continue;  // the neighbour is culled: nothing of it is drawn
        EXPECT_EQ(bits(a[k]), bits(b[kOpposite[k]]))
            << at << " edge " << k << ": " << a[k] << " vs " << b[kOpposite[k]];
        EXPECT_EQ(bits(a[k]), bits(std::min(a[4], b[4]))) << at << " edge " << k << " is min of the inner levels";
        ++compared;
      }
    }
  return compared / 2;  // each shared edge was visited from both sides
}

std::vector<CameraPose> shippedPathPoses() {
  std::vector<CameraPose> poses;
  for (const char* name : {"flyover", "lowalt", "horizon"}) {
    CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name + ".csv");
    int frames = frameCount(path, 30);
    for (int f : {0, frames / 3, 2 * frames / 3, frames - 1}) poses.push_back(samplePose(path, 30, f, testTerrain()));
  }
  return poses;
}

class InterlockScheme : public lbtest::GpuTest {};

}  // namespace

// Without culling every patch is drawn, so all 2 n (n - 1) shared edges are compared on each frame.
TEST_F(InterlockScheme, SharedEdgesBitIdenticalOnShippedPathsWithoutCulling) {
  const int n = 16;
  Renderer r(gpu(), testTerrain(), {160, 90, n});
  r.setScheme(*findScheme("interlock"), {{"cull", 0}});
  auto poses = shippedPathPoses();
  poses.push_back(lbtest::poseAt({-100, 250, -100}, {500, 0, 500}));
  poses.push_back(lbtest::poseAt({520, 40, 480}, {900, 0, 100}, 90));  // inside dmin: saturated LODs
  for (size_t k = 0; k < poses.size(); ++k) {
    int compared = checkInterlocked(captureLevels(r, poses[k]), n, poses[k], {}, "pose " + std::to_string(k));
    EXPECT_EQ(compared, 2 * n * (n - 1)) << "pose " << k;
  }
}

// With culling (the default) the rules hold between every pair of drawn patches.
TEST_F(InterlockScheme, SharedEdgesBitIdenticalWithCullingAndOtherRanges) {
  const int n = 16;
  Renderer r(gpu(), testTerrain(), {160, 90, n});
  const LodParams wide{0, 0.8, 2, 64};
  r.setScheme(*findScheme("interlock"), {{"dmin", 0}, {"dmax", 0.8}, {"min_lod", 2}, {"max_lod", 64}});
  int culledFrames = 0;
  for (const CameraPose& pose : shippedPathPoses()) {
    auto lv = captureLevels(r, pose);
    int culled = 0;
    for (int p = 0; p < n * n; ++p) culled += lv[size_t(p) * kStride + 4] == 0.0f;
    culledFrames += culled > 0;
    EXPECT_GT(checkInterlocked(lv, n, pose, wide, "path pose"), 0);
  }
  EXPECT_GT(culledFrames, 0) << "some frame should cull patches, else this test repeats the one above";
}

// The camera sits half a cell off the patch centre, away from side k. With dmin between the
// near midpoints' distances and the far one's, the own patch and three neighbours saturate at
// max_lod (= 16 exactly) and only the neighbour across side k is lower: only outer[k] may drop.
TEST_F(InterlockScheme, LowerNeighbourLandsOnTheOuterLevelFacingIt) {
  const int n = 8, pi = 3, pj = 4;  // i != j so a transposed mapping would pick the wrong patch
  const double cell = testTerrain().extent / n;
  Renderer r(gpu(), testTerrain(), {160, 90, n});
  for (int side = 0; side < 4; ++side) {
    glm::dvec3 own = cellMidpoint(pi, pj, n);
    glm::vec3 eye(own + glm::dvec3(-0.5 * cell * kSideDi[side], 30.0, -0.5 * cell * kSideDj[side]));
    double nearMax = glm::distance(own, glm::dvec3(eye)), far = 0;
    for (int k = 0; k < 4; ++k) {
      double d = glm::distance(cellMidpoint(pi + kSideDi[k], pj + kSideDj[k], n), glm::dvec3(eye));
      if (k == side)
        far = d;
      else
        nearMax = std::max(nearMax, d);
    }
    ASSERT_GT(far, nearMax + 10.0) << "side " << side << ": the set-up needs one clearly farther neighbour";
    const double extent = testTerrain().extent;
    LodParams p{(nearMax + far) / 2 / extent, (nearMax + far) / 2 / extent + 1, 1, 16};
    r.setScheme(*findScheme("interlock"),
                {{"dmin", p.minDistance}, {"dmax", p.maxDistance}, {"min_lod", 1}, {"max_lod", 16}, {"cull", 0}});
    auto pose = lbtest::poseAt(eye, glm::vec3(own) + glm::vec3(1, -30, 1));
    auto lv = captureLevels(r, pose);
    const float* a = &lv[size_t(pj * n + pi) * kStride];
    const float* far_patch = &lv[size_t((pj + kSideDj[side]) * n + pi + kSideDi[side]) * kStride];
    EXPECT_EQ(a[4], 16.0f) << "side " << side << ": inner is the saturated own LOD";
    EXPECT_EQ(a[5], 16.0f) << "side " << side;
    for (int k = 0; k < 4; ++k) {
      if (k == side) {
        EXPECT_LT(a[k], 16.0f) << "side " << side << ": the farther neighbour's lower LOD is missing";
        EXPECT_GT(a[k], 1.0f) << "side " << side;
        EXPECT_EQ(bits(a[k]), bits(far_patch[4])) << "side " << side << ": outer = that neighbour's inner";
        EXPECT_NEAR(a[k], referenceLod(cellMidpoint(pi + kSideDi[k], pj + kSideDj[k], n), eye, p), 1e-3);
      } else {
        EXPECT_EQ(a[k], 16.0f) << "side " << side << ": outer[" << k << "] faces a neighbour at max_lod";
      }
    }
  }
}

// Clear-colour pixels not 8-connected to the image border: background showing through inside the
// terrain. Silhouette notches touch the sky and are not counted; cracks between patches are.
int enclosedClearPixels(const std::vector<uint8_t>& px, int w, int h) {
  auto isClear = [&](int x, int y) {
    const uint8_t* c = &px[size_t(y * w + x) * 4];
    return c[0] == 255 && c[1] == 0 && c[2] == 255;
  };
  std::vector<uint8_t> reached(size_t(w * h), 0);
  std::vector<int> stack;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if ((x == 0 || y == 0 || x == w - 1 || y == h - 1) && isClear(x, y)) {
        reached[size_t(y * w + x)] = 1;
        stack.push_back(y * w + x);
      }
  while (!stack.empty()) {
    int p = stack.back();
    stack.pop_back();
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int x = p % w + dx, y = p / w + dy;
        if (x < 0 || y < 0 || x >= w || y >= h || reached[size_t(y * w + x)] || !isClear(x, y)) continue;
        reached[size_t(y * w + x)] = 1;
        stack.push_back(y * w + x);
      }
  }
  int enclosed = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) enclosed += isClear(x, y) && !reached[size_t(y * w + x)];
  return enclosed;
}

// Image check on the shipped paths with a steep LOD falloff (many edges between unequal levels).
TEST_F(InterlockScheme, NoCracksInShadedImages) {
  const int n = 16, w = 320, h = 180;
  Renderer r(gpu(), testTerrain(), {w, h, n});
  r.setScheme(*findScheme("interlock"), {{"dmin", 0}, {"dmax", 0.7}, {"max_lod", 9}});
  for (const CameraPose& pose : shippedPathPoses()) {
    auto px = r.renderImage(pose, pose, RenderMode::Shaded);
    EXPECT_EQ(enclosedClearPixels(px, w, h), 0);
  }
}

// Shared-renderer guard found by this scheme: a draw longer than kMaxIndicesPerDraw restarts
// gl_PrimitiveID on lavapipe, so captured levels (and culling bounds) land on the wrong patches.
// Every topology's draws stay within one segment, and a 32^2 interlock grid (1024 patches, 12
// indices each) keeps its captured inner levels on the right patches.
TEST_F(InterlockScheme, DrawsNeverRestartPrimitiveIds) {
  EXPECT_EQ(kMaxIndicesPerDraw / controlPointCount(Topology::Quad12), 85u);
  const int n = 32;
  Renderer r(gpu(), testTerrain(), {64, 64, n});
  r.setScheme(*findScheme("interlock"), {{"cull", 0}, {"max_lod", 4}});
  EXPECT_LE(r.patchesPerDraw() * 12, kMaxIndicesPerDraw);
  EXPECT_EQ(r.drawCount(), (1024u + 84u) / 85u);
  auto pose = lbtest::poseAt({-100, 300, 200}, {500, 0, 500});
  auto lv = captureLevels(r, pose);
  for (int p = 0; p < n * n; ++p)
    ASSERT_NEAR(lv[size_t(p) * kStride + 4], referenceLod(cellMidpoint(p % n, p / n, n), pose.eye, {0.1, 1.5, 1, 4}),
                1e-3)
        << "patch " << p;
}
