// Crack metrics (docs/design.md, What is measured): the analytic count from captured levels and the image count
// against the `reference` scheme. A deliberately cracking test scheme must trip both; the registry
// schemes (sphere-rings only with its power-of-2 clamp) must trip neither.
#include <unistd.h>

#include <cstdio>

#include "crack_scheme.h"
#include "gpu_fixture.h"
#include "metrics/cracks.h"
#include "metrics/edge_pattern.h"
#include "metrics/mesh_cracks.h"
#include "render/patch_grid.h"
#include "shaders/shared.h"

using namespace lb;
using lbtest::gpu;
using lbtest::testTerrain;

namespace {

// Levels where every slot of every patch differs from every other: each shared edge mismatches.
std::vector<float> distinctLevels(int n, Topology t) {
  std::vector<float> lv(size_t(patchCountFor(n, t)) * LB_CAPTURE_STRIDE);
  for (size_t i = 0; i < lv.size(); ++i) lv[i] = 1.0f + float(i) / 8.0f;
  return lv;
}

struct Frame {
  RgbaImage image;
  std::vector<float> levels;
};

Frame renderFrame(Renderer& r, const CameraPose& pose) {
  const RenderSettings& s = r.settings();
  Frame f{{s.width, s.height, r.renderImage(pose, pose, RenderMode::Shaded)}, {}};
  f.levels = r.capturedLevels();
  return f;
}

std::vector<CameraPose> shippedPoses() {
  std::vector<CameraPose> poses;
  for (const char* name : {"flyover", "lowalt", "horizon"}) {
    CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name + ".csv");
    int frames = frameCount(path, 30);
    for (int f : {frames / 3, 2 * frames / 3}) poses.push_back(samplePose(path, 30, f, testTerrain()));
  }
  return poses;
}

}  // namespace

// An n x n grid has n (n - 1) vertical and n (n - 1) horizontal shared edges, and Tri3 adds the n^2
// diagonals; with all levels distinct every one of them is a crack, and culling one patch removes
// exactly the shared edges it has (interior quad: 4; interior Tri3 triangle: 3).
TEST(GridCrackEdges, CountsEverySharedEdgeOnce) {
  const int n = 5;
  std::vector<float> quads = distinctLevels(n, Topology::Quad4);
  EXPECT_EQ(gridCrackEdges(Topology::Quad4, n, quads), 2 * n * (n - 1));
  EXPECT_EQ(gridCrackEdges(Topology::Quad12, n, quads), 2 * n * (n - 1));
  std::vector<float> tris = distinctLevels(n, Topology::Tri3);
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, tris), n * n + 2 * n * (n - 1));

  const size_t centre = 2 * n + 2;  // quad (2, 2)
  for (int k = 0; k < 4; ++k) quads[centre * LB_CAPTURE_STRIDE + size_t(k)] = 0;
  EXPECT_EQ(gridCrackEdges(Topology::Quad4, n, quads), 2 * n * (n - 1) - 4);
  tris[2 * centre * LB_CAPTURE_STRIDE] = 0;  // one outer level <= 0 discards the triangle
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, tris), n * n + 2 * n * (n - 1) - 3);

  std::vector<float> same(size_t(patchCountFor(n, Topology::Tri3)) * LB_CAPTURE_STRIDE, 7.5f);
  EXPECT_EQ(gridCrackEdges(Topology::Quad4, n, same), 0);
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, same), 0);
  EXPECT_THROW(gridCrackEdges(Topology::Tri3, n + 1, same), std::invalid_argument);
}

// Tri3 pairs are the right edges: only the perturbed slot of one triangle breaks one shared edge.
TEST(GridCrackEdges, Tri3PairsFollowTheCornerOrder) {
  const int n = 3;
  std::vector<float> lv(size_t(patchCountFor(n, Topology::Tri3)) * LB_CAPTURE_STRIDE, 4.0f);
  auto slot = [&](int i, int j, int t, int k) -> float& {
    return lv[size_t(2 * (j * n + i) + t) * LB_CAPTURE_STRIDE + size_t(k)];
  };
  slot(1, 1, 0, 1) = 5;  // A's diagonal 00-11 against B of the same quad
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, lv), 1);
  slot(1, 1, 1, 2) = 5;  // ... and B's 00-11 now agrees again
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, lv), 0);
  slot(1, 1, 0, 0) = 6, slot(2, 1, 1, 1) = 6;  // x = 2 edge: A of (1,1), B of (2,1)
  slot(1, 1, 0, 2) = 7, slot(1, 0, 1, 0) = 7;  // z = 1 edge: A of (1,1), B of (1,0)
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, lv), 0);
  slot(2, 1, 0, 0) = 9;  // x = 3: the terrain border, shared with nobody
  EXPECT_EQ(gridCrackEdges(Topology::Tri3, n, lv), 0);
}

TEST(CrackMask, RedOnCracksOverADimmedFrame) {
  RgbaImage frame{2, 1, {90, 30, 255, 255, 255, 0, 255, 255}};
  RgbaImage m = crackMaskImage(frame, {0, 1});
  EXPECT_EQ(m.px, (std::vector<uint8_t>{30, 10, 85, 255, 255, 0, 0, 255}));
  EXPECT_THROW(crackMaskImage(frame, {1}), std::invalid_argument);
}

class Cracks : public lbtest::GpuTest {};

// The test scheme changes outer[2] of every patch (i, j) with i + j even, which is the edge shared
// with (i + 1, j) when i + 1 < n; unperturbed shared edges keep the sphere level, bit-identical on
// both sides (SphereLod.SharedEdgesGetIdenticalLevels). So the analytic count is the number of
// such (i, j) whose pair is drawn. Seen whole (nothing culled) an 8 x 8 grid has, per row, i in
// {0, 2, 4, 6} (j even) or {1, 3, 5} (j odd) below 7: 4 x 4 + 4 x 3 = 28.
TEST_F(Cracks, CrackingSchemeTripsBothDetectors) {
  const int n = 8, w = 160, h = 90;
  const Heightfield& hf = testTerrain();
  Renderer r(gpu(), hf, {w, h, n}), ref(gpu(), hf, {w, h, n});
  const ParamValues params = resolveParams(lbtest::crackScheme().info(), {{"tri_size", 6}});
  r.setScheme(lbtest::crackScheme(), params);
  ref.setScheme(*findScheme("reference"), {});
  struct Case {
    CameraPose pose;
    bool whole;
  };
  for (const Case& c : {Case{lbtest::poseAt({500, 900, -100}, {500, 0, 500}), true},
                        Case{lbtest::poseAt({300, 160, 100}, {600, 40, 600}), false}}) {
    Frame f = renderFrame(r, c.pose);
    long expected = 0, culled = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        size_t p = size_t(j * n + i);
        culled += !patchDrawn(f.levels, p, Topology::Quad4);
        expected += (i + j) % 2 == 0 && i + 1 < n && patchDrawn(f.levels, p, Topology::Quad4) &&
                    patchDrawn(f.levels, p + 1, Topology::Quad4);
      }
    if (c.whole) {
      ASSERT_EQ(culled, 0) << "premise: the whole terrain is in view";
      EXPECT_EQ(expected, 28);
    } else {
      ASSERT_GT(culled, 0) << "premise: some patches are culled";
      ASSERT_GT(expected, 0);
    }
    EXPECT_EQ(analyticCracks(lbtest::crackScheme(), params, hf, n, f.levels), expected);
    RgbaImage reference{w, h, ref.renderImage(c.pose, c.pose, RenderMode::Shaded)};
    std::vector<uint8_t> mask;
    long pixels = crackPixels(f.image, reference, &mask);
    EXPECT_GT(pixels, 0);
    RgbaImage overlay = crackMaskImage(f.image, mask);
    long red = 0;
    for (size_t i = 0; i < mask.size(); ++i)
      red += overlay.px[i * 4] == 255 && overlay.px[i * 4 + 1] == 0 && overlay.px[i * 4 + 2] == 0;
    EXPECT_EQ(red, pixels) << "dimmed pixels are never pure red";
    std::string png = "/tmp/lodbench_crack_mask_" + std::to_string(getpid()) + ".png";
    writeCrackMaskPng(png, f.image, mask);
    EXPECT_EQ(std::remove(png.c_str()), 0) << "the mask PNG was written";
  }
}

// Crack-free schemes: zero analytic cracks and zero crack pixels on frames of every shipped path.
// The reference scheme's own frames are the reference images (zero crack pixels by definition).
TEST_F(Cracks, RegistrySchemesHaveNoCracksOnShippedPaths) {
  const int n = 8, w = 160, h = 90;
  const Heightfield& hf = testTerrain();
  const Scheme& reference = *findScheme("reference");
  Renderer ref(gpu(), hf, {w, h, n});
  ref.setScheme(reference, {});
  std::vector<CameraPose> poses = shippedPoses();
  std::vector<RgbaImage> refImages;
  for (const CameraPose& pose : poses) {
    Frame f = renderFrame(ref, pose);
    EXPECT_EQ(analyticCracks(reference, {}, hf, n, f.levels), 0);
    refImages.push_back(f.image);
  }
  for (const Scheme* s : lbtest::drawableSchemes()) {
    if (s == &reference) continue;
    Renderer r(gpu(), hf, {w, h, n});
    ParamValues params = resolveParams(s->info(), {});
    r.setScheme(*s, params);
    for (size_t k = 0; k < poses.size(); ++k) {
      SCOPED_TRACE(s->info().name + " pose " + std::to_string(k));
      Frame f = renderFrame(r, poses[k]);
      if (s->info().path != DrawPath::Tessellation) {  // the drawn mesh, as the measurement pass checks it
        r.measureHistogram(poses[k], poses[k]);
        EXPECT_EQ(meshCracks(r.capturedMesh(), {glm::vec2(0.0f), glm::vec2(hf.extent)}).crackSites, 0);
      } else {
        EXPECT_EQ(analyticCracks(*s, params, hf, n, f.levels), 0);
      }
      EXPECT_EQ(crackPixels(f.image, refImages[k]), 0);
    }
  }
}

// As SphereRingsGpu.PowerOfTwoClampRemovesBoundaryCracksOnEveryShippedPath, on the flyover: without
// the power-of-2 clamp a small side with an odd level S puts S + 1 fractional_even segments against
// the large side's S equal halves (level 2 S), so exactly the ring boundaries with a drawn odd
// small side mismatch (equal-size shared edges always agree); with the clamp none do.
TEST_F(Cracks, SphereRingsCrackOnlyWithoutPowerOfTwoClamp) {
  const Scheme& rings = *findScheme("sphere-rings");
  const Heightfield& hf = testTerrain();
  const int grid = 128;
  CameraPath path = loadCameraPath(LODBENCH_SOURCE_DIR "/configs/paths/flyover.csv");
  const int frames = frameCount(path, 30);
  for (int pow2 : {1, 0}) {
    SCOPED_TRACE("pow2 = " + std::to_string(pow2));
    ParamValues params = resolveParams(rings.info(), {{"tri_size", 1}, {"pow2", pow2}});
    Renderer r(gpu(), hf, {160, 90, grid});
    r.setScheme(rings, params);
    PatchGeometry g = rings.patchGeometry(hf, params, grid);
    long total = 0;
    for (int k = 0; k < 4; ++k) {
      Frame f = renderFrame(r, samplePose(path, 30, k * (frames - 1) / 3, hf));
      auto drawn = [&](const PatchSide& s) { return patchDrawn(f.levels, s.patch, Topology::Quad4); };
      auto level = [&](const PatchSide& s) { return f.levels[s.patch * LB_CAPTURE_STRIDE + size_t(s.side)]; };
      long oddBoundaries = 0;
      for (const HalfBoundary& b : quadPatchEdges(g).half) {
        bool oddLo = drawn(b.lo) && int(level(b.lo)) % 2 == 1, oddHi = drawn(b.hi) && int(level(b.hi)) % 2 == 1;
        oddBoundaries += drawn(b.large) && (oddLo || oddHi);
      }
      long cracks = analyticCracks(rings, params, hf, grid, f.levels);
      EXPECT_EQ(cracks, pow2 ? 0 : oddBoundaries) << "frame " << k;
      total += cracks;
    }
    if (!pow2) EXPECT_GT(total, 0);
  }
}
