// cbt (schemes/cbt.cpp): the neighbour rule against geometry, convergence to a fixed point, the
// conformity of every leaf set, the drawn triangles (leaves x 4^subd), and the replay the harness
// measures a stateful scheme with.
#include <filesystem>
#include <fstream>

#include "cbt_reference.h"
#include "gpu_fixture.h"
#include "metrics/mesh_cracks.h"
#include "replay/lod_replay.h"
#include "shaders/cbt_params.h"

using namespace lb;
using namespace lbtest;

namespace {
class Cbt : public GpuTest {};

const Scheme& cbtScheme() {
  return *findScheme("cbt");
}

CameraPose firstPose(const std::string& file, const Heightfield& hf) {
  CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + file);
  return samplePose(path, 30, 0, hf);
}
}  // namespace

TEST(CbtReference, NeighbourRuleMatchesTheGeometryDownToDepth16) {
  EXPECT_EQ(cbt::checkNeighbourRule(16), "");
}

TEST(CbtReference, ConformityCheckFindsAHangingVertex) {
  // Node 2 split alone (children 4, 5) beside the unsplit node 3: a T-junction on the diagonal.
  EXPECT_EQ(cbt::conformity({2, 3}, 4), "");
  EXPECT_EQ(cbt::conformity({4, 5, 6, 7}, 4), "");
  EXPECT_NE(cbt::conformity({4, 5, 3}, 4), "");
}

// Static camera at frame 0 of every shipped path: converged within the limit, then a byte-identical
// tree for four more updates; every leaf conforms and the frame draws leaves x 4^subd triangles.
TEST_F(Cbt, ConvergesOnEveryShippedPathThenHoldsItsTreeAndConforms) {
  const Heightfield& hf = testTerrain();
  Renderer r(gpu(), hf, {160, 90, 16});
  r.setScheme(cbtScheme(), {});
  const uint32_t limit = r.convergeLimit();
  const uint32_t depth = r.readLodState()[LB_CBT_DEPTH];
  EXPECT_EQ(limit, 2 * depth + 8);
  for (const std::string& file : shippedPathFiles()) {
    const CameraPose pose = firstPose(file, hf);
    ConvergeResult c = convergeLod(r, pose);
    EXPECT_TRUE(c.converged) << file << ": " << c.updates << " updates";
    EXPECT_LE(c.updates, int(limit)) << file;
    const std::vector<uint32_t> settled = cbt::withoutCounter(r.readLodState());
    for (int i = 0; i < 4; ++i) {
      r.updateLod(pose);
      EXPECT_EQ(cbt::withoutCounter(r.readLodState()), settled) << file << ": update " << i << " moved the tree";
    }
    const std::vector<uint32_t> state = r.readLodState();
    const std::vector<uint32_t> leaves = cbt::leaves(state);
    EXPECT_EQ(leaves.size(), state[LB_CBT_LEAVES]) << file;
    EXPECT_LE(leaves.size(), state[LB_CBT_CAPACITY]) << file;
    EXPECT_EQ(cbt::conformity(leaves, state[LB_CBT_LATTICE_LOG2]), "") << file;
    EXPECT_GT(leaves.size(), 2u) << file << ": the tree never refined";
    // One more frame (an update at the fixed point changes nothing) draws them all.
    FrameResult f = renderOnce(r, pose);
    EXPECT_EQ(f.instances, leaves.size()) << file;
    EXPECT_EQ(f.stats.clipInvocations, f.instances * 64u) << file << ": subd 3 is 64 triangles a leaf";
    TriangleHistogram h = r.measureHistogram(pose, pose);
    EXPECT_EQ(h.total(), f.stats.clipInvocations) << file;
    EXPECT_EQ(meshCracks(r.capturedMesh(), {glm::vec2(0.0f), glm::vec2(hf.extent)}).crackSites, 0) << file;
  }
}

// Every frame of a moving camera: leaves within the capacity, triangles = leaves x 4^subd, a
// conforming tree after every update, and a replay from the snapshot meets every count again.
TEST_F(Cbt, EveryUpdateAlongAPathConformsAndTheReplayMeetsIt) {
  const Heightfield& hf = testTerrain();
  Renderer r(gpu(), hf, {160, 90, 16});
  r.setScheme(cbtScheme(), {{"tri_size", 4}, {"subd", 2}});
  CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/dive.csv");
  auto pose = [&](int f) { return samplePose(path, 10, f, hf); };
  const int frames = std::min(frameCount(path, 10), 40);
  convergeLod(r, pose(0));
  r.snapshotLodState();
  std::vector<uint32_t> timed;
  for (int f = 0; f < frames; ++f) {
    FrameResult fr = renderOnce(r, pose(f));
    timed.push_back(uint32_t(fr.instances));
    EXPECT_EQ(fr.stats.clipInvocations, fr.instances * 16u) << "frame " << f;
    const std::vector<uint32_t> state = r.readLodState();
    EXPECT_EQ(state[LB_CBT_OVERFLOW], 0u);
    EXPECT_EQ(cbt::conformity(cbt::leaves(state), state[LB_CBT_LATTICE_LOG2]), "") << "frame " << f;
  }
  LodReplay replay(r, pose, timed);
  EXPECT_NO_THROW(replay.advanceTo(frames - 1));
  // A replay that expects other counts fails loudly.
  std::vector<uint32_t> wrong = timed;
  wrong[size_t(frames / 2)] += 1;
  LodReplay bad(r, pose, wrong);
  try {
    bad.advanceTo(frames - 1);
    ADD_FAILURE() << "a diverging replay passed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("LOD replay diverged"), std::string::npos) << e.what();
  }
}
