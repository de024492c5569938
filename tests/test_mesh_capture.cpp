// The measurement pass captures the drawn mesh of a path with instances (analytic cracks read it)
// in one storage buffer of at most 2 GiB, 44.7 M triangles. A frame that draws more (a fine
// configuration of a tuned search on a large terrain) keeps its counts and histogram; only its
// mesh is left out, and the metric that reads it becomes null with the reason.
#include <gtest/gtest.h>

#include <string>

#include "error.h"
#include "gpu_fixture.h"
#include "render/renderer.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"

namespace lb {
namespace {

class MeshCapture : public lbtest::GpuTest {};

TEST_F(MeshCapture, AFramePastTheCaptureKeepsItsHistogramAndLeavesOnlyTheMeshOut) {
  TerrainSpec spec;
  spec.size = 257;
  spec.seed = 3;
  spec.extent = 1000;
  spec.heightScale = 150;
  const Heightfield hf = makeProcedural(spec);
  RenderSettings whole{160, 90, 8};
  RenderSettings small = whole;
  small.testMeshCaptureMost = 64;
  const CameraPose pose = lbtest::poseAt({-100, 300, -100}, {500, 0, 500});
  for (const char* name : {"cdlod", "cbt"}) {
    Renderer a(lbtest::gpu(), hf, whole), b(lbtest::gpu(), hf, small);
    a.setScheme(*findScheme(name), {});
    b.setScheme(*findScheme(name), {});
    const TriangleHistogram ha = a.measureHistogram(pose, pose), hb = b.measureHistogram(pose, pose);
    const size_t drawn = a.capturedMesh().size() / 3;
    ASSERT_GT(drawn, 64u) << name << ": the frame must overflow the small capture";
    EXPECT_EQ(ha.bins, hb.bins) << name;
    EXPECT_EQ(ha.offscreen, hb.offscreen) << name;
    EXPECT_EQ(ha.backfacing, hb.backfacing) << name;
    try {
      (void)b.capturedMesh();
      ADD_FAILURE() << name << ": the lost mesh must not read as a mesh";
    } catch (const FeatureMissing& e) {
      EXPECT_NE(std::string(e.what()).find("drew " + std::to_string(drawn) + " triangles"), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("at most 64"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace lb
