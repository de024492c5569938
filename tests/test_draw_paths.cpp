// The instanced-grid draw path against the tessellation path: `uniform` drawn as instanced grids
// (render/uniform_instanced.h) must give uniform's triangles, histogram totals and error pixels, and
// one instanced draw past lavapipe's 16-bit limits must equal the same work in many draws.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "gpu_fixture.h"
#include "render/renderer.h"
#include "render/uniform_instanced.h"
#include "stats.h"

using namespace lb;
using namespace lbtest;
namespace fs = std::filesystem;

namespace {

class DrawPaths : public GpuTest {};

}  // namespace

// Level x grid = 128 = the 129^2 test terrain's sample spacing: one vertex per texel on both paths.
// Diagonal 2 is the tessellator's triangulation of an integer quad domain on lavapipe (diagonals
// flip between the patch's quadrants); the other three give p99 differences of 0.07-3 px here, so the
// test also shows the check would catch a different triangulation.
TEST_F(DrawPaths, InstancedUniformDrawsUniformsTrianglesAndErrorOnEveryShippedPath) {
  const Heightfield& hf = testTerrain();
  const int grid = 16, level = 8;
  Renderer tess(gpu(), hf, {160, 90, grid});
  Renderer inst(gpu(), hf, {160, 90, grid});
  tess.setScheme(*findScheme("uniform"), {{"level", level}});
  inst.setScheme(uniformInstancedScheme(), {{"level", level}, {"diagonal", 2}});
  int frames = 0;
  for (const std::string& name : shippedPathFiles()) {
    const std::string file = std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name;
    CameraPath path = loadCameraPath(file);
    const int n = frameCount(path, 30);
    for (int f = 0; f < n; f += 20) {
      CameraPose pose = samplePose(path, 30, f, hf);
      // Rasterization is discarded in the histogram pass, so clipping counts come from a drawn frame.
      FrameResult rt = renderOnce(tess, pose), ri = renderOnce(inst, pose);
      TriangleHistogram ht = tess.measureHistogram(pose, pose);
      TriangleHistogram hi = inst.measureHistogram(pose, pose);
      ASSERT_EQ(rt.stats.clipInvocations, ri.stats.clipInvocations) << file << " frame " << f;
      ASSERT_EQ(ht.total(), hi.total()) << file << " frame " << f;
      ASSERT_EQ(hi.total(), ri.stats.clipInvocations) << file << " frame " << f;
      EXPECT_EQ(ri.instances, uint64_t(grid) * grid);
      EXPECT_EQ(inst.capturedMesh().size(), size_t(ri.stats.clipInvocations) * 3);
      std::vector<float> et = tess.renderErrorMap(pose, pose), ei = inst.renderErrorMap(pose, pose);
      std::vector<double> diff;
      size_t coverageDiffers = 0, terrain = 0;
      for (size_t p = 0; p < et.size(); ++p) {
        if ((et[p] < 0) != (ei[p] < 0)) ++coverageDiffers;
        if (et[p] >= 0 && ei[p] >= 0) {
          diff.push_back(std::abs(double(et[p]) - double(ei[p])));
          ++terrain;
        }
      }
      // The tessellator's domain coordinates are fixed point, the lattice's exact: positions differ
      // in the last bits, so silhouettes may move by a pixel here and there, and errors by far less.
      EXPECT_LE(coverageDiffers, et.size() / 1000 + 2) << file << " frame " << f;
      EXPECT_LE(percentile(diff, 99), 0.01) << file << " frame " << f << " (" << terrain << " terrain pixels)";
      ++frames;
    }
  }
  EXPECT_GT(frames, 20);
}

// 64 instances of a 65 x 65-vertex footprint: 270,400 vertices in one draw (past 65,535) against the
// same triangles cut into 64 footprints per patch (4,096 draws' worth of rows, 64 draws).
TEST_F(DrawPaths, OneLargeInstancedDrawEqualsTheSameWorkInManyDraws) {
  const Heightfield& hf = testTerrain();
  Renderer one(gpu(), hf, {160, 90, 8});
  Renderer many(gpu(), hf, {160, 90, 8});
  one.setScheme(uniformInstancedScheme(), {{"level", 64}, {"split", 1}});
  many.setScheme(uniformInstancedScheme(), {{"level", 64}, {"split", 64}});
  CameraPose pose = overviewPose();
  FrameResult r1, rm;
  std::vector<uint8_t> a = one.renderImage(pose, pose, RenderMode::Shaded, &r1);
  std::vector<uint8_t> b = many.renderImage(pose, pose, RenderMode::Shaded, &rm);
  EXPECT_EQ(r1.draws, 1u);
  EXPECT_EQ(rm.draws, 64u);
  EXPECT_GT(r1.stats.vsInvocations, 65535u);
  EXPECT_EQ(r1.stats.clipInvocations, uint64_t(8 * 8) * 64 * 64 * 2);
  EXPECT_EQ(r1.stats.clipInvocations, rm.stats.clipInvocations);
  EXPECT_EQ(r1.stats.fsInvocations, rm.stats.fsInvocations);
  EXPECT_TRUE(a == b) << "pixels differ between one draw and 64";
  TriangleHistogram h1 = one.measureHistogram(pose, pose), hm = many.measureHistogram(pose, pose);
  EXPECT_EQ(h1.bins, hm.bins);
  EXPECT_EQ(h1.total(), hm.total());
}

// The instanced path times its LOD apart from its draws; tessellation has no such split.
TEST_F(DrawPaths, InstancedFramesReportLodAndDrawTimesTessellationDoesNot) {
  const Heightfield& hf = testTerrain();
  Renderer tess(gpu(), hf, {64, 64, 8});
  Renderer inst(gpu(), hf, {64, 64, 8});
  tess.setScheme(*findScheme("uniform"), {{"level", 4}});
  inst.setScheme(uniformInstancedScheme(), {{"level", 4}});
  FrameResult t = renderOnce(tess, overviewPose()), i = renderOnce(inst, overviewPose());
  EXPECT_EQ(t.lodMs, -1);
  EXPECT_EQ(t.drawMs, -1);
  EXPECT_EQ(t.lodCpuMs, -1);
  EXPECT_EQ(t.instances, 0u);
  EXPECT_GE(i.lodMs, 0);
  EXPECT_GE(i.drawMs, 0);
  EXPECT_GE(i.lodCpuMs, 0);
  EXPECT_NEAR(i.lodMs + i.drawMs, i.gpuMs, 1e-6 + 1e-9 * i.gpuMs);
  EXPECT_EQ(i.instances, 64u);
  EXPECT_EQ(i.draws, 1u);
}
