// sphere-rings: the ring layout (doubling tiles, adjacency scalars, covering the terrain from every
// admissible centre), the per-frame centre that follows the LOD camera, and the seed's claim that
// only power-of-2 levels make tessellation patterns meet across ring boundaries, on every shipped
// path.
#include <algorithm>
#include <cmath>
#include <set>

#include "camera/camera_matrices.h"
#include "crop_rows.h"
#include "error.h"
#include "gpu_fixture.h"
#include "metrics/cracks.h"
#include "metrics/edge_pattern.h"
#include "render/patch_grid.h"
#include "schemes/sphere_rings_layout.h"
#include "shaders/shared.h"
#include "shaders/sphere_rings_params.h"
#include "terrain/heightfield.h"
#include "threads_env.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

const Scheme& rings() {
  return *findScheme("sphere-rings");
}

PatchGeometry layout(const ParamValues& given, int grid) {
  return rings().patchGeometry(testTerrain(), resolveParams(rings().info(), given), grid);
}

const float* record(const PatchGeometry& g, size_t p) {
  return &g.schemeBuffer[size_t(kRingHeaderFloats) + p * kRingFloatsPerPatch];
}

glm::ivec2 centreOf(const FrameUniforms& u) {
  return {int(u.params[LB_SPHERE_RINGS_CENTRE_X / 4][LB_SPHERE_RINGS_CENTRE_X % 4]),
          int(u.params[LB_SPHERE_RINGS_CENTRE_Z / 4][LB_SPHERE_RINGS_CENTRE_Z % 4])};
}

// The centre update() packs for an LOD eye, as the renderer's fillUniforms calls it.
glm::ivec2 packedCentre(glm::vec3 eye, int grid, const ParamValues& given = {}) {
  FrameUniforms u{};
  u.lodEye = glm::vec4(eye, 1);
  u.terrain = glm::vec4(testTerrain().extent, float(grid), 0, 0);
  rings().update(u, resolveParams(rings().info(), given));
  return centreOf(u);
}

std::vector<CameraPose> shippedPathPoses(int perPath) {
  std::vector<CameraPose> poses;
  for (const char* name : {"flyover", "lowalt", "horizon"}) {
    CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name + ".csv");
    int frames = frameCount(path, 30);
    for (int k = 0; k < perPath; ++k)
      poses.push_back(samplePose(path, 30, k * (frames - 1) / (perPath - 1), testTerrain()));
  }
  return poses;
}

}  // namespace

// The culling bounds of every ring level: ring 0's cells scan their samples, coarser levels combine
// 2 x 2 finer cells. Each cell must hold what scanning its own rectangle gives (the range of every
// sample its bilinear surface touches), on grids that are not powers of two (lattices whose last
// cells are partial or past the terrain), a non-square terrain and an extent that is no round
// number, with the terrain read on 1 or 3 threads.
TEST(SphereRingsLayout, RingBoundsEqualEachCellsOwnScan) {
  TerrainSpec spec;
  spec.size = 97;
  spec.seed = 6;
  spec.extent = 777.7f;
  spec.heightScale = 90;
  const Heightfield hf = lbtest::cropRows(makeProcedural(spec), 61);
  for (const Heightfield* t : {&testTerrain(), &hf})
    for (int grid : {48, 96, 200, 256})
      for (int threads : {1, 3}) {
        ThreadsEnv env(threads);
        const std::string what = std::to_string(t->width) + "x" + std::to_string(t->height) + ", grid " +
                                 std::to_string(grid) + ", " + std::to_string(threads) + " threads";
        const ParamValues v = resolveParams(rings().info(), {});
        const PatchGeometry g = rings().patchGeometry(*t, v, grid);
        const int rcount = ringCount(v, grid);
        ASSERT_GT(rcount, 1) << what;
        const double unit = double(t->extent) / grid;
        long compared = 0;
        for (int r = 0; r < rcount; ++r) {
          const long n = ringLatticeSize(grid, r), step = 1L << r;
          const size_t at = size_t(g.schemeBuffer[size_t(r)]) * 2;
          ASSERT_LE(at + size_t(2 * n * n), g.schemeBuffer.size()) << what;
          for (long j = 0; j < n; ++j)
            for (long i = 0; i < n; ++i) {
              const glm::vec2 want =
                  rectHeightBounds(*t, glm::vec2(float(i * step * unit), float(j * step * unit)),
                                   glm::vec2(float((i + 1) * step * unit), float((j + 1) * step * unit)));
              const size_t k = at + size_t(2 * (j * n + i));
              ASSERT_EQ(g.schemeBuffer[k], want.x) << what << ", ring " << r << ", cell " << i << ", " << j;
              ASSERT_EQ(g.schemeBuffer[k + 1], want.y) << what << ", ring " << r << ", cell " << i << ", " << j;
              ++compared;
            }
        }
        EXPECT_GT(compared, grid * grid) << what;
      }
}

// Ring r is an 8x8-tile square of patches 2^r lattice units wide (a 4x4-tile hole after ring 0),
// centred on the lattice origin, so its outer half-width is 32 2^r: a point's ring follows from
// its Chebyshev distance to the origin. The default ring count is the fewest whose outermost ring
// covers the terrain (grid lattice units) from any centre in [0, grid].
TEST(SphereRingsLayout, RingsTileSizesAdjacencyAndCoverage) {
  for (int grid : {16, 32, 64, 128, 256}) {
    SCOPED_TRACE("grid " + std::to_string(grid));
    const int rcount = ringCount(resolveParams(rings().info(), {}), grid);
    ASSERT_EQ(rcount, grid <= 32 ? 1 : 1 + int(std::ceil(std::log2(grid / 32.0))));
    PatchGeometry g = layout({}, grid);
    const size_t n = g.bounds.size();
    ASSERT_EQ(g.indices.size(), 4 * n);
    ASSERT_GE(g.schemeBuffer.size(), kRingHeaderFloats + kRingFloatsPerPatch * n);
    auto ringAt = [&](double x, double z) {
      double d = std::max(std::abs(x), std::abs(z));
      for (int r = 0; r < rcount; ++r)
        if (d < 32 * std::ldexp(1.0, r)) return r;
      return -1;
    };
    int twice = 0, half = 0;
    for (size_t p = 0; p < n; ++p) {
      const float* rp = record(g, p);
      PatchRect r = patchRect(g, p);
      int ring = ringAt(0.5 * (r.x0 + r.x1), 0.5 * (r.z0 + r.z1));
      const float size = float(std::ldexp(1.0, ring));  // patches double ring by ring
      ASSERT_EQ(rp[6], float(ring));
      ASSERT_EQ(r.x1 - r.x0, size);
      ASSERT_EQ(r.z1 - r.z0, size);
      ASSERT_TRUE(rp[4] >= 0 && rp[4] < 8 && rp[5] >= 0 && rp[5] < 8);
      bool border[4] = {rp[4] == 0, rp[5] == 0, rp[4] == 7, rp[5] == 7};
      float across[4][2] = {{r.x0 - size / 4, 0.5f * (r.z0 + r.z1)},
                            {0.5f * (r.x0 + r.x1), r.z0 - size / 4},
                            {r.x1 + size / 4, 0.5f * (r.z0 + r.z1)},
                            {0.5f * (r.x0 + r.x1), r.z1 + size / 4}};
      for (int s = 0; s < 4; ++s) {
        float adj = rp[s];
        EXPECT_TRUE(adj == 0.5f || adj == 1.0f || adj == 2.0f) << adj;
        if (!border[s]) continue;  // the tile's scalar only applies on its border
        int other = ringAt(across[s][0], across[s][1]);
        float expected = other < 0 ? 1.0f : float(std::ldexp(1.0, other - ring));
        ASSERT_EQ(adj, expected) << "patch " << p << " side " << s;
        twice += adj == 2.0f;
        half += adj == 0.5f;
      }
    }
    auto boundaries = quadPatchEdges(g).half;
    EXPECT_EQ(boundaries.size(), size_t(half));
    EXPECT_EQ(twice, 2 * half);
    for (auto& b : boundaries) {  // the adjacency scalars describe exactly these edges
      EXPECT_EQ(record(g, b.large.patch)[b.large.side], 0.5f);
      EXPECT_EQ(record(g, b.lo.patch)[b.lo.side], 2.0f);
      EXPECT_EQ(record(g, b.hi.patch)[b.hi.side], 2.0f);
    }
    // From every admissible centre the patches over the terrain tile it exactly, once.
    const int coarsest = 1 << (rcount - 1);
    for (int k : {0, coarsest, grid / coarsest / 2 * coarsest, grid / coarsest * coarsest}) {
      double area = 0;
      for (size_t p = 0; p < n; ++p) {
        PatchRect r = patchRect(g, p);
        double x0 = std::max(0.0, double(r.x0) + k), x1 = std::min(double(grid), double(r.x1) + k);
        double z0 = std::max(0.0, double(r.z0) + k), z1 = std::min(double(grid), double(r.z1) + k);
        if (x1 > x0 && z1 > z0) area += (x1 - x0) * (z1 - z0);
      }
      EXPECT_EQ(area, double(grid) * grid) << "centre " << k;
    }
  }
}

// An explicit ring count too small to cover the terrain from every centre is an input error.
TEST(SphereRingsLayout, TooFewRingsForTheGridIsAnInputError) {
  EXPECT_THROW(layout({{"rings", 2}}, 128), InputError);
  EXPECT_NO_THROW(layout({{"rings", 3}}, 128));
  EXPECT_NO_THROW(layout({{"rings", 4}}, 64));  // more than needed: the extra rings never reach the terrain
}

// The centre is the LOD eye snapped to a multiple of the coarsest patch (2^(R-1) lattice units),
// within half of one from the eye over the terrain, and clamped to the terrain beyond it.
TEST(SphereRingsCentre, SnapsToTheCoarsestPatchAndFollowsTheEye) {
  const float extent = testTerrain().extent;
  for (int grid : {32, 128, 256}) {
    const int rcount = ringCount(resolveParams(rings().info(), {}), grid), coarsest = 1 << (rcount - 1);
    const double unit = extent / grid;
    for (float x : {0.0f, 123.4f, 500.0f, 777.7f, 1000.0f})
      for (float z : {0.0f, 61.0f, 999.0f}) {
        glm::ivec2 k = packedCentre({x, 300, z}, grid);
        EXPECT_EQ(k, ringCentre({x, z}, extent, grid, rcount));
        EXPECT_EQ(k.x % coarsest, 0);
        EXPECT_EQ(k.y % coarsest, 0);
        EXPECT_LE(std::abs(k.x * unit - x), 0.5 * coarsest * unit + 1e-3) << grid << " " << x;
        EXPECT_LE(std::abs(k.y * unit - z), 0.5 * coarsest * unit + 1e-3) << grid << " " << z;
      }
    EXPECT_EQ(packedCentre({-5000, 10, 9000}, grid), glm::ivec2(0, grid / coarsest * coarsest));
  }
  // Scale-free: the same eye relative to the extent gives the same centre.
  EXPECT_EQ(ringCentre({123.4, 777.7}, 1000, 128, 3), ringCentre({1.234, 7.777}, 10, 128, 3));
  EXPECT_EQ(ringCentre({123.4, 777.7}, 1000, 128, 3), ringCentre({12340, 77770}, 100000, 128, 3));
}

class SphereRingsGpu : public lbtest::GpuTest {};

// Drawn patches lie on the terrain wherever the camera is, the finest ring is under the camera,
// and the patches the camera sits on are finer than those far from it.
TEST_F(SphereRingsGpu, RingsFollowTheCameraAndStayOnTheTerrain) {
  const int grid = 128;
  const Heightfield& hf = testTerrain();
  PatchGeometry g = layout({}, grid);
  Renderer r(gpu(), hf, {160, 90, grid});
  r.setScheme(rings(), {});
  for (glm::vec2 xz : {glm::vec2(150, 180), glm::vec2(820, 700), glm::vec2(500, 500)}) {
    SCOPED_TRACE("eye " + std::to_string(xz.x) + ", " + std::to_string(xz.y));
    glm::vec3 eye(xz.x, hf.sample(xz.x, xz.y) + 200, xz.y);
    // Steeply down towards the terrain's centre (+x from the centre): the ground under the camera
    // is in view (69 + 45 degrees below the horizon), and so is ground over 250 away (ring 1).
    glm::vec2 dir = xz == glm::vec2(500, 500) ? glm::vec2(1, 0) : glm::normalize(glm::vec2(500, 500) - xz);
    glm::vec2 at = xz + 75.0f * dir;
    auto pose = lbtest::poseAt(eye, glm::vec3(at.x, hf.sample(xz.x, xz.y), at.y), 90);
    r.renderImage(pose, pose, RenderMode::Shaded);
    std::vector<float> lv = r.capturedLevels();
    const glm::ivec2 k = packedCentre(eye, grid);
    const glm::vec2 eyeCell = xz / (hf.extent / grid);
    // Culling follows the moved rings: a patch is dropped exactly when it is off the terrain or
    // its box (exact height bounds of its moved footprint) lies outside the LOD frustum.
    CameraMatrices m = cameraMatrices(pose, 160.0f / 90.0f, hf.extent);
    glm::vec4 planes[6];
    frustumPlanes(m.proj * m.view, planes);
    const float unit = hf.extent / grid;
    int compared = 0;
    for (size_t p = 0; p < g.bounds.size(); ++p) {
      PatchRect rc = patchRect(g, p);
      glm::vec2 lo(rc.x0 + k.x, rc.z0 + k.y), hi(rc.x1 + k.x, rc.z1 + k.y);
      if (lo.x < 0 || lo.y < 0 || lo.x >= grid || lo.y >= grid) {
        EXPECT_FALSE(patchDrawn(lv, p, Topology::Quad4)) << "patch " << p << " off the terrain";
        continue;
      }
      glm::vec2 b = rectHeightBounds(hf, lo * unit, hi * unit);
      float nearest = INFINITY;  // signed distance of the box's farthest corner inside each plane
      for (const glm::vec4& pl : planes) {
        glm::vec3 v(pl.x >= 0 ? hi.x * unit : lo.x * unit, pl.y >= 0 ? b.y : b.x,
                    pl.z >= 0 ? hi.y * unit : lo.y * unit);
        nearest = std::min(nearest, glm::dot(glm::vec3(pl), v) + pl.w);
      }
      if (std::abs(nearest) < 1e-3f * hf.extent) continue;  // float-close to a plane: either is right
      EXPECT_EQ(patchDrawn(lv, p, Topology::Quad4), nearest > 0) << "patch " << p;
      ++compared;
    }
    EXPECT_GT(compared, 1000);
    int drawn = 0, underEye = -1, farRing = 0;
    for (size_t p = 0; p < g.bounds.size(); ++p) {
      if (!patchDrawn(lv, p, Topology::Quad4)) continue;
      ++drawn;
      PatchRect rc = patchRect(g, p);
      EXPECT_TRUE(rc.x0 + k.x >= 0 && rc.z0 + k.y >= 0 && rc.x1 + k.x <= grid && rc.z1 + k.y <= grid)
          << "patch " << p << " drawn off the terrain";
      int ring = int(record(g, p)[6]);
      if (eyeCell.x >= rc.x0 + k.x && eyeCell.x < rc.x1 + k.x && eyeCell.y >= rc.z0 + k.y && eyeCell.y < rc.z1 + k.y)
        underEye = ring;
      farRing = std::max(farRing, ring);
    }
    EXPECT_GT(drawn, 100);
    EXPECT_EQ(underEye, 0) << "the patch under the camera is in the finest ring";
    EXPECT_GT(farRing, 0) << "coarser rings are drawn further away";
    EXPECT_EQ(analyticCracks(rings(), r.params(), hf, grid, lv), 0);
  }
}

// Every shipped path, grid 128 (three rings), 1 px triangles so ring boundaries see levels around
// 4-6: both sides of a boundary derive their level from the same large edge (integers, large =
// 2 x small); with the power-of-2 clamp no boundary mismatches on any frame; without it some
// frame of every path has odd small-side levels, and exactly those boundaries crack.
TEST_F(SphereRingsGpu, PowerOfTwoClampRemovesBoundaryCracksOnEveryShippedPath) {
  const int grid = 128, perPath = 4;
  const Heightfield& hf = testTerrain();
  PatchGeometry g = layout({}, grid);
  const auto boundaries = quadPatchEdges(g).half;
  const auto poses = shippedPathPoses(perPath);
  for (int pow2 : {1, 0}) {
    SCOPED_TRACE("pow2 = " + std::to_string(pow2));
    const ParamValues params = resolveParams(rings().info(), {{"tri_size", 1}, {"pow2", pow2}});
    Renderer r(gpu(), hf, {160, 90, grid});
    r.setScheme(rings(), params);
    for (int path = 0; path < 3; ++path) {
      long pathCracks = 0;
      int compared = 0;
      for (int f = 0; f < perPath; ++f) {
        const CameraPose& pose = poses[size_t(path * perPath + f)];
        r.renderImage(pose, pose, RenderMode::Shaded);
        std::vector<float> lv = r.capturedLevels();
        auto level = [&](const PatchSide& s) { return lv[s.patch * LB_CAPTURE_STRIDE + size_t(s.side)]; };
        auto drawn = [&](const PatchSide& s) { return patchDrawn(lv, s.patch, Topology::Quad4); };
        long odd = 0, mismatched = 0, halvesCracked = 0;
        for (const HalfBoundary& b : boundaries) {
          if (!drawn(b.large)) continue;
          // metrics/cracks.h: a boundary cracks when a drawn small side misses its half's vertices.
          halvesCracked += (drawn(b.lo) && !fractionalEvenHalfMatches(level(b.large), level(b.lo), 0)) ||
                           (drawn(b.hi) && !fractionalEvenHalfMatches(level(b.large), level(b.hi), 1));
          if (!drawn(b.lo) || !drawn(b.hi)) continue;
          float large = level(b.large), small0 = level(b.lo), small1 = level(b.hi);
          ++compared;
          EXPECT_EQ(small0, small1);
          EXPECT_EQ(large, 2 * small0);
          EXPECT_EQ(small0, std::floor(small0));
          if (pow2) {
            EXPECT_EQ(small0, std::exp2(std::round(std::log2(small0)))) << "not a power of 2";
          }
          odd += int(small0) % 2;
          mismatched += !fractionalEvenPatternsMatch(large, small0, small1);
        }
        EXPECT_EQ(mismatched, odd) << "exactly the odd small-side levels mismatch";
        long cracks = analyticCracks(rings(), params, hf, grid, lv);
        EXPECT_EQ(cracks, halvesCracked) << "path " << path << " frame " << f << ": equal-size edges never crack";
        EXPECT_GE(cracks, mismatched);
        pathCracks += cracks;
      }
      EXPECT_GT(compared, 20) << "path " << path << ": ring boundaries in view";
      if (pow2) {
        EXPECT_EQ(pathCracks, 0) << "path " << path;
      } else {
        EXPECT_GT(pathCracks, 0) << "path " << path;
      }
    }
  }
}

// Inside a ring neighbours share corners and compute the same sphere level: identical factors.
TEST_F(SphereRingsGpu, EqualSizeNeighboursShareLevels) {
  const int grid = 128;
  PatchGeometry g = layout({}, grid);
  Renderer r(gpu(), testTerrain(), {160, 90, grid});
  r.setScheme(rings(), {{"pow2", 0}});
  auto pose = lbtest::poseAt({-100, 400, -100}, {500, 0, 500});
  r.renderImage(pose, pose, RenderMode::Shaded);
  std::vector<float> lv = r.capturedLevels();
  int compared = 0;
  for (const auto& [a, b] : quadPatchEdges(g).equal) {
    if (lv[a.patch * LB_CAPTURE_STRIDE + 4] == 0 || lv[b.patch * LB_CAPTURE_STRIDE + 4] == 0) continue;
    EXPECT_EQ(lv[a.patch * LB_CAPTURE_STRIDE + size_t(a.side)], lv[b.patch * LB_CAPTURE_STRIDE + size_t(b.side)]);
    ++compared;
  }
  EXPECT_GT(compared, 1000);
}
