// The GPU-indirect draw path: compute passes write instances and draw arguments on the GPU, the
// renderer draws them indirectly, times the passes apart (lod_ms), and resets, snapshots and
// restores the LOD state they keep across frames.
#include "gpu_fixture.h"
#include "gpu_lod_scheme.h"
#include "metrics/mesh_cracks.h"
#include "render/lod_state.h"
#include "render/uniform_instanced.h"

using namespace lb;
using namespace lbtest;

namespace {
class GpuIndirect : public GpuTest {};
}  // namespace

// Culled patches lie outside the frustum: the image equals the CPU-instanced path's, which draws
// every patch; the GPU's count decides the triangles, each instance its whole footprint.
TEST_F(GpuIndirect, DrawsWhatTheGpuSelectedAndTheSamePixelsAsTheCpuPath) {
  const Heightfield& hf = testTerrain();
  const int grid = 16, level = 4;
  Renderer gpuPath(gpu(), hf, {160, 90, grid});
  Renderer cpuPath(gpu(), hf, {160, 90, grid});
  gpuPath.setScheme(gpuUniformScheme(), {{"level", level}});
  cpuPath.setScheme(uniformInstancedScheme(), {{"level", level}, {"diagonal", 2}});
  CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/lowalt.csv");
  bool someCulled = false;
  for (int f = 0; f < frameCount(path, 30); f += 30) {
    CameraPose pose = samplePose(path, 30, f, hf);
    FrameResult g, c;
    std::vector<uint8_t> a = gpuPath.renderImage(pose, pose, RenderMode::Shaded, &g);
    std::vector<uint8_t> b = cpuPath.renderImage(pose, pose, RenderMode::Shaded, &c);
    EXPECT_TRUE(a == b) << "frame " << f;
    EXPECT_LE(g.instances, uint64_t(grid * grid));
    EXPECT_GT(g.instances, 0u);
    someCulled = someCulled || g.instances < uint64_t(grid * grid);
    EXPECT_EQ(g.stats.clipInvocations, g.instances * uint64_t(2 * level * level)) << "frame " << f;
    EXPECT_EQ(g.draws, 1u);
    EXPECT_GE(g.lodMs, 0.0);
    EXPECT_GE(g.drawMs, 0.0);
    EXPECT_EQ(g.lodCpuMs, -1.0) << "no CPU selection on this path";
    // The measurement passes see the same mesh: histogram total, capture and its crack check.
    TriangleHistogram h = gpuPath.measureHistogram(pose, pose);
    EXPECT_EQ(h.total(), g.stats.clipInvocations);
    EXPECT_EQ(gpuPath.capturedMesh().size(), size_t(g.stats.clipInvocations) * 3);
    EXPECT_EQ(meshCracks(gpuPath.capturedMesh(), {glm::vec2(0.0f), glm::vec2(hf.extent)}).crackSites, 0);
    // Without a reader of the mesh (keepMesh false) the same histogram, and no mesh copied.
    EXPECT_EQ(gpuPath.measureHistogram(pose, pose, nullptr, false).total(), h.total());
    EXPECT_TRUE(gpuPath.capturedMesh().empty());
  }
  EXPECT_TRUE(someCulled) << "lowalt culls part of the grid: the count must come from the GPU";
}

TEST_F(GpuIndirect, StateIsResetSnapshottedAndRestored) {
  Renderer r(gpu(), testTerrain(), {64, 64, 8});
  r.setScheme(gpuUniformScheme(), {{"level", 2}});
  auto updates = [&] { return r.lodState().read()[0]; };
  EXPECT_EQ(updates(), 0u);
  for (int i = 0; i < 3; ++i) renderOnce(r, overviewPose());
  EXPECT_EQ(updates(), 3u);
  r.lodState().snapshot();
  for (int i = 0; i < 2; ++i) renderOnce(r, overviewPose());
  EXPECT_EQ(updates(), 5u);
  r.lodState().restore();
  EXPECT_EQ(updates(), 3u);
  renderOnce(r, overviewPose());
  EXPECT_EQ(updates(), 4u);
  // keep() sets a copy aside beside the snapshot; putBack() restores it and leaves the snapshot.
  EXPECT_THROW(r.lodState().putBack(), std::logic_error) << "nothing kept yet";
  r.lodState().keep();
  for (int i = 0; i < 2; ++i) renderOnce(r, overviewPose());
  EXPECT_EQ(updates(), 6u);
  r.lodState().putBack();
  EXPECT_EQ(updates(), 4u);
  r.lodState().restore();
  EXPECT_EQ(updates(), 3u);
  r.lodState().reset();
  EXPECT_EQ(updates(), 0u);
  const std::vector<uint32_t> state = r.lodState().read();
  ASSERT_EQ(state.size(), 4u);
  EXPECT_EQ(state[3], uint32_t(2 * 2 * 6)) << "the footprint's index count, as the scheme set it";
  // The hooks refuse a scheme without GPU state.
  Renderer t(gpu(), testTerrain(), {64, 64, 8});
  t.setScheme(*findScheme("uniform"), {});
  EXPECT_THROW(t.lodState().snapshot(), std::logic_error);
}
