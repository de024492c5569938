// sphere-rings: exact ring layout (patch counts, doubling tile sizes, adjacency scalars) and the
// seed's claim that only power-of-2 levels make tessellation patterns meet across ring boundaries.
#include <algorithm>
#include <cmath>
#include <set>

#include "gpu_fixture.h"
#include "metrics/edge_pattern.h"
#include "shaders/shared.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

constexpr int kFloatsPerPatch = 8;  // RingPatch: adjacency[4], patch x, patch z, ring, patch size

const Scheme& rings() {
  return *findScheme("sphere-rings");
}

PatchGeometry layout(const ParamValues& given) {
  return rings().patchGeometry(testTerrain(), resolveParams(rings().info(), given));
}

}  // namespace

// Ring r is an 8x8-tile square of tile size tile0 * 2^r (a 4x4-tile hole after ring 0), so its
// outer half-width is 4 tile0 2^r: which ring holds a point follows from its Chebyshev distance to
// the centre. With tile_size 0 the outermost ring spans the extent: tile0 = extent / (8 2^(R-1)).
TEST(SphereRingsLayout, PatchCountsTileSizesAndAdjacencyScalars) {
  const float extent = testTerrain().extent, centre = 0.5f * extent;
  for (int rcount = 1; rcount <= 4; ++rcount) {
    PatchGeometry g = layout({{"rings", rcount}});
    const size_t n = g.bounds.size();
    // 64 tiles in ring 0, 64 - 16 in every further ring, 64 patches per tile.
    ASSERT_EQ(n, size_t(64 * (64 + 48 * (rcount - 1)))) << rcount << " rings";
    ASSERT_EQ(g.indices.size(), 4 * n);
    ASSERT_EQ(g.schemeBuffer.size(), kFloatsPerPatch * n);
    const double tile0 = extent / (8.0 * std::ldexp(1.0, rcount - 1));
    auto ringAt = [&](double x, double z) {
      double d = std::max(std::abs(x - centre), std::abs(z - centre));
      for (int r = 0; r < rcount; ++r)
        if (d < 4 * tile0 * std::ldexp(1.0, r)) return r;
      return -1;  // outside every ring
    };
    double area = 0;
    int twice = 0, half = 0;
    for (size_t p = 0; p < n; ++p) {
      const float* rp = &g.schemeBuffer[p * kFloatsPerPatch];
      PatchRect r = patchRect(g, p);
      int ring = ringAt(0.5 * (r.x0 + r.x1), 0.5 * (r.z0 + r.z1));
      double size = tile0 / 8 * std::ldexp(1.0, ring);  // tiles double ring by ring
      ASSERT_EQ(rp[6], float(ring));
      ASSERT_EQ(double(r.x1 - r.x0), size);
      ASSERT_EQ(double(r.z1 - r.z0), size);
      ASSERT_EQ(double(rp[7]), size);
      area += size * size;
      ASSERT_TRUE(rp[4] >= 0 && rp[4] < 8 && rp[5] >= 0 && rp[5] < 8);
      bool border[4] = {rp[4] == 0, rp[5] == 0, rp[4] == 7, rp[5] == 7};
      float across[4][2] = {{r.x0 - float(size) / 4, 0.5f * (r.z0 + r.z1)},
                            {0.5f * (r.x0 + r.x1), r.z0 - float(size) / 4},
                            {r.x1 + float(size) / 4, 0.5f * (r.z0 + r.z1)},
                            {0.5f * (r.x0 + r.x1), r.z1 + float(size) / 4}};
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
    EXPECT_EQ(area, double(extent) * extent) << "the rings tile the terrain exactly";
    // Per ring boundary: 4 sides x 8 tiles x 8 patches see a larger neighbour, 4 x 4 x 8 a smaller one.
    EXPECT_EQ(twice, 256 * (rcount - 1));
    EXPECT_EQ(half, 128 * (rcount - 1));
    auto boundaries = quadPatchEdges(g).half;
    EXPECT_EQ(boundaries.size(), size_t(half));
    for (auto& b : boundaries) {  // the adjacency scalars describe exactly these edges
      EXPECT_EQ(g.schemeBuffer[b.large.patch * kFloatsPerPatch + size_t(b.large.side)], 0.5f);
      EXPECT_EQ(g.schemeBuffer[b.lo.patch * kFloatsPerPatch + size_t(b.lo.side)], 2.0f);
      EXPECT_EQ(g.schemeBuffer[b.hi.patch * kFloatsPerPatch + size_t(b.hi.side)], 2.0f);
    }
  }
}

// Shared corners are shared vertices, and patches wholly outside the terrain are dropped.
TEST(SphereRingsLayout, SharedCornersAndClipping) {
  PatchGeometry g = layout({{"rings", 2}});
  // Ring 0: 65^2 corners. Ring 1 (64x64 patches, 32x32 hole): 65^2 - 31^2 corners, of which the
  // 4 x 32 on the hole's border are every other corner of ring 0's border, so already there.
  EXPECT_EQ(g.vertices.size(), size_t(65 * 65 + (65 * 65 - 31 * 31) - 4 * 32));
  // One ring of tile size extent / 4 spans [-500, 1500]: 32x32 of its 64x64 patches touch the terrain.
  PatchGeometry big = layout({{"rings", 1}, {"tile_size", 0.25}});
  EXPECT_EQ(big.bounds.size(), 32u * 32u);
  for (size_t p = 0; p < big.bounds.size(); ++p) {
    PatchRect r = patchRect(big, p);
    EXPECT_TRUE(r.x0 >= 0 && r.z0 >= 0 && r.x1 <= 1000 && r.z1 <= 1000);
    EXPECT_LE(big.bounds[p].x, testTerrain().sample(r.x0, r.z0));
    EXPECT_GE(big.bounds[p].y, testTerrain().sample(0.5f * (r.x0 + r.x1), 0.5f * (r.z0 + r.z1)));
  }
}

class SphereRingsGpu : public lbtest::GpuTest {};

// Two rings of tile size extent / 16: ring 0 spans [250, 750]^2, ring 1 the rest of the terrain;
// 128 large ring-1 edges on that square's border each meet two ring-0 edges. The camera stands
// just outside the corner (750, 750) and looks along the boundary x = 750 towards z = 500, so the
// boundary recedes from it. A large edge's sphere level there is T ~ 0.5 * 90 px * 15.6 /
// (depth * tan 30 deg) / tri_size 1 = 1218 / depth: from over 13 near the corner down to about 2.
// Neighbouring edges are 15.6 apart, so T steps by about T^2 * 15.6 / 1218, under 0.5 while
// T <= 6: some edge has T in (4, 6], and the integer+even clamp gives it the small-side level
// ceil(T / 2) = 3. fractional_even rounds an odd level S up to S + 1 segments, so two such edges
// put 2 S + 3 vertices against the large edge's 2 S + 1: a mismatch wherever the implementation
// puts the short segments. Powers of 2 are even: every level is a whole number of equal segments.
TEST_F(SphereRingsGpu, PowerOfTwoClampRemovesBoundaryMismatches) {
  const ParamValues base = {{"rings", 2}, {"tile_size", 1.0 / 16}, {"tri_size", 1}};
  const Heightfield& hf = testTerrain();
  glm::vec3 eye(770, hf.sample(770, 790) + 40, 790), target(745, hf.sample(745, 500), 500);
  auto pose = lbtest::poseAt(eye, target);
  for (int pow2 : {1, 0}) {
    SCOPED_TRACE("pow2 = " + std::to_string(pow2));
    ParamValues params = base;
    params["pow2"] = pow2;
    PatchGeometry g = layout(params);
    Renderer r(gpu(), hf, {160, 90, 1});
    r.setScheme(rings(), params);
    ASSERT_EQ(r.patchCount(), g.bounds.size());
    r.renderImage(pose, pose, RenderMode::Shaded);
    std::vector<float> lv = r.capturedLevels();
    auto level = [&](size_t p, int s) { return lv[p * LB_CAPTURE_STRIDE + size_t(s)]; };
    auto visible = [&](size_t p) { return level(p, 4) > 0; };
    for (size_t p = 0; p < g.bounds.size(); ++p)
      for (int s = 0; s < 6; ++s) ASSERT_TRUE(level(p, s) == 0 || (level(p, s) >= 1 && level(p, s) <= 64));
    int compared = 0, mismatched = 0, odd = 0;
    std::set<float> smallLevels;
    for (const HalfBoundary& b : quadPatchEdges(g).half) {
      if (!visible(b.large.patch) || !visible(b.lo.patch) || !visible(b.hi.patch)) continue;
      float large = level(b.large.patch, b.large.side), small0 = level(b.lo.patch, b.lo.side),
            small1 = level(b.hi.patch, b.hi.side);
      ++compared;
      // Both sides derive their level from the same large edge: integers with large = 2 x small.
      EXPECT_EQ(small0, small1);
      EXPECT_EQ(large, 2 * small0);
      EXPECT_EQ(small0, std::floor(small0));
      if (pow2) {
        EXPECT_EQ(small0, std::exp2(std::round(std::log2(small0)))) << "not a power of 2";
      }
      smallLevels.insert(small0);
      odd += int(small0) % 2;
      mismatched += !fractionalEvenPatternsMatch(large, small0, small1);
    }
    EXPECT_GT(compared, 40);
    if (pow2) {
      EXPECT_EQ(mismatched, 0);
    } else {
      EXPECT_EQ(smallLevels.count(3.0f), 1u) << "premise: some boundary edge has T in (4, 6]";
      EXPECT_GT(mismatched, 0);
      EXPECT_EQ(mismatched, odd) << "exactly the odd small-side levels mismatch";
    }
  }
}

// Inside a ring neighbours share corners and compute the same sphere level: identical factors.
TEST_F(SphereRingsGpu, EqualSizeNeighboursShareLevels) {
  const ParamValues params = {{"rings", 2}, {"tile_size", 1.0 / 16}, {"pow2", 0}};
  PatchGeometry g = layout(params);
  Renderer r(gpu(), testTerrain(), {160, 90, 1});
  r.setScheme(rings(), params);
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
