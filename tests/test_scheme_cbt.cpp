// cbt (schemes/cbt.cpp): the neighbour rule against geometry, convergence to a fixed point, the
// conformity of every leaf set, the drawn triangles (leaves x 4^subd), and the replay the harness
// measures a stateful scheme with.
#include <filesystem>
#include <fstream>

#include "cbt_reference.h"
#include "error.h"
#include "gpu_fixture.h"
#include "metrics/mesh_cracks.h"
#include "render/draw_limits.h"
#include "render/lod_state.h"
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
  const uint32_t limit = r.lodState().gpuLod().convergeLimit;
  const uint32_t depth = r.lodState().read()[LB_CBT_DEPTH];
  EXPECT_EQ(limit, 2 * depth + 8);
  for (const std::string& file : shippedPathFiles()) {
    const CameraPose pose = firstPose(file, hf);
    ConvergeResult c = convergeLod(r, pose);
    EXPECT_TRUE(c.converged) << file << ": " << c.updates << " updates";
    EXPECT_LE(c.updates, int(limit)) << file;
    const std::vector<uint32_t> settled = cbt::withoutCounter(r.lodState().read());
    for (int i = 0; i < 4; ++i) {
      r.lodState().update(pose);
      EXPECT_EQ(cbt::withoutCounter(r.lodState().read()), settled) << file << ": update " << i << " moved the tree";
    }
    const std::vector<uint32_t> state = r.lodState().read();
    const std::vector<uint32_t> leaves = cbt::leaves(state);
    EXPECT_EQ(leaves.size(), state[LB_CBT_LEAVES]) << file;
    EXPECT_LE(leaves.size(), state[LB_CBT_CAPACITY]) << file;
    EXPECT_EQ(cbt::conformity(leaves, state[LB_CBT_LATTICE_LOG2]), "") << file;
    EXPECT_GT(leaves.size(), 2u) << file << ": the tree never refined";
    // One more frame (an update at the fixed point changes nothing) draws them all.
    FrameResult f = renderOnce(r, pose);
    FrozenLod frozen(r);
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
  r.lodState().snapshot();
  std::vector<uint32_t> timed;
  for (int f = 0; f < frames; ++f) {
    FrameResult fr = renderOnce(r, pose(f));
    timed.push_back(uint32_t(fr.instances));
    EXPECT_EQ(fr.stats.clipInvocations, fr.instances * 16u) << "frame " << f;
    const std::vector<uint32_t> state = r.lodState().read();
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

// cbt-ts: the same tree on every frame (the whole state, byte for byte), each leaf tessellated into
// the ring layout's T(2^subd) triangles, split into draws of at most kMaxVerticesPerDraw / (n+1)^2
// patches, and as closed as cbt's mesh.
TEST_F(Cbt, CbtTsDrawsExactlyCbtsLeavesThroughTheTessellator) {
  const Heightfield& hf = testTerrain();
  CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/lowalt.csv");
  auto pose = [&](int f) { return samplePose(path, 10, f, hf); };
  const ParamValues params = {{"tri_size", 2}, {"subd", 3}, {"cells_per_texel", 4}};
  Renderer instanced(gpu(), hf, {320, 180, 16}), tessellated(gpu(), hf, {320, 180, 16});
  instanced.setScheme(cbtScheme(), params);
  tessellated.setScheme(*findScheme("cbt-ts"), params);
  convergeLod(instanced, pose(0));
  convergeLod(tessellated, pose(0));
  auto rings = [](int n) {  // the triangle domain's triangles at integer level n
    int t = n % 2;
    for (int k = 2 - n % 2; k <= n; k += 2) t += 6 * (k - 1);
    return uint64_t(t);
  };
  ASSERT_EQ(rings(1), 1u);
  ASSERT_EQ(rings(2), 6u);
  ASSERT_EQ(rings(3), 13u);
  const uint64_t perDraw = kMaxVerticesPerDraw / 81;
  const int frames = std::min(frameCount(path, 10), 30);
  bool severalDraws = false;
  for (int f = 0; f < frames; ++f) {
    FrameResult a = renderOnce(instanced, pose(f)), b = renderOnce(tessellated, pose(f));
    std::vector<uint32_t> treeA = instanced.lodState().read(), treeB = tessellated.lodState().read();
    treeA[LB_CBT_INDEX_COUNT] = treeB[LB_CBT_INDEX_COUNT] = 0;  // their leaf meshes differ
    EXPECT_EQ(treeA, treeB) << "frame " << f;
    EXPECT_EQ(b.instances, a.instances) << "frame " << f;
    EXPECT_EQ(a.stats.clipInvocations, a.instances * 64u) << "frame " << f;
    EXPECT_EQ(b.stats.clipInvocations, b.instances * rings(8)) << "frame " << f;
    EXPECT_EQ(b.draws, (b.instances + perDraw - 1) / perDraw) << "frame " << f;
    severalDraws = severalDraws || b.draws > 1;
    if (f % 10 == 0) {
      FrozenLod frozen(tessellated);  // a measurement draws the state, it does not update it
      TriangleHistogram h = tessellated.measureHistogram(pose(f), pose(f));
      EXPECT_EQ(h.total(), b.stats.clipInvocations) << "frame " << f;
      EXPECT_EQ(meshCracks(tessellated.capturedMesh(), {glm::vec2(0.0f), glm::vec2(hf.extent)}).crackSites, 0)
          << "frame " << f;
    }
  }
  EXPECT_TRUE(severalDraws) << "no frame needed more than one draw: the split is untested";
}

// Seen from above, little of a heightfield faces away (steep flanks near the image border): under 5%
// of the on-screen triangles are back-facing for cbt and cbt-ts, as for the tessellated uniform
// grid. A leaf mesh wound the other way puts nearly all of them there, out of the size bins.
TEST_F(Cbt, FromAboveEveryTriangleFacesTheCamera) {
  const Heightfield& hf = testTerrain();
  const CameraPose pose = firstPose("topdown.csv", hf);
  for (const char* name : {"uniform", "cbt", "cbt-ts"}) {
    Renderer r(gpu(), hf, {160, 90, 16});
    r.setScheme(*findScheme(name), {});
    if (r.statefulLod()) convergeLod(r, pose);
    FrozenLod frozen(r);
    TriangleHistogram h = r.measureHistogram(pose, pose);
    const uint64_t onScreen = h.total() - h.offscreen;
    EXPECT_GT(onScreen, 100u) << name;
    EXPECT_LT(h.backfacing * 20, onScreen) << name << ": " << h.backfacing << " of " << onScreen << " back-facing";
  }
}

// Leaves beyond the record capacity are never drawn silently: planted by loading a state whose
// capacity is 4 leaves, the replay of the next update fails with "LOD state overflow".
TEST_F(Cbt, LeavesBeyondTheCapacityFailTheReplay) {
  const Heightfield& hf = testTerrain();
  Renderer r(gpu(), hf, {160, 90, 16});
  r.setScheme(cbtScheme(), {});
  const CameraPose pose = overviewPose();
  convergeLod(r, pose);
  EXPECT_EQ(r.lodState().overflow(), 0u);
  std::vector<uint32_t> state = r.lodState().read();
  ASSERT_GT(state[LB_CBT_LEAVES], 4u);
  state[LB_CBT_CAPACITY] = 4;
  r.lodState().load(state);
  r.lodState().snapshot();
  LodReplay replay(r, [&](int) { return pose; }, {});
  try {
    replay.advanceTo(0);
    ADD_FAILURE() << "the overflow passed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("LOD state overflow"), std::string::npos) << e.what();
  }
}

namespace {
// A heightfield's shape alone: cbtTree reads the size and the height range, never the samples.
Heightfield shape(int samples) {
  Heightfield hf;
  hf.width = hf.height = samples;
  hf.minHeight = 0.0f, hf.maxHeight = 100.0f;
  return hf;
}
GpuLod cbtLod(int samples, const ParamValues& given, const GpuLodBudget& budget, const char* scheme = "cbt") {
  const Scheme& s = *findScheme(scheme);
  return s.gpuLod(shape(samples), resolveParams(s.info(), given), budget);
}
double fact(const GpuLod& g, const std::string& key) {
  for (const auto& [k, v] : g.facts)
    if (k == key) return v;
  ADD_FAILURE() << "no fact " << key;
  return -1;
}
}  // namespace

// The pool rule (schemes/cbt.cpp): capacity = min(pool, 2^D, the device's most), the pool 4 x the
// viewport's face-on leaves at tri_size, a power of two of at least 2^17; large_cbt's four pools
// come out at 1920 x 1080, subd 3 between t = 4 and 1.4 px, 8M at the least t.
TEST(CbtPool, CapacityFollowsTheTerrainTheViewBudgetAndTheDevice) {
  const GpuLodBudget hd{1920, 1080};
  struct Row {
    int samples;
    double t;
    uint32_t depth, pool, capacity;
  };
  for (const Row& r : {Row{257, 7, 11, 1u << 17, 1u << 11}, Row{4097, 7, 19, 1u << 17, 1u << 17},
                       Row{4097, 0.5, 19, 1u << 23, 1u << 19}, Row{16385, 7, 23, 1u << 17, 1u << 17},
                       Row{16385, 4, 23, 1u << 17, 1u << 17}, Row{16385, 2.9, 23, 1u << 18, 1u << 18},
                       Row{16385, 2, 23, 1u << 19, 1u << 19}, Row{16385, 1.5, 23, 1u << 20, 1u << 20},
                       Row{16385, 0.5, 23, 1u << 23, 1u << 23}}) {
    for (const char* scheme : {"cbt", "cbt-ts"}) {
      const GpuLod g = cbtLod(r.samples, {{"tri_size", r.t}}, hd, scheme);
      const std::string at = std::string(scheme) + " " + std::to_string(r.samples) + "^2 t " + std::to_string(r.t);
      EXPECT_EQ(fact(g, "cbt_depth"), r.depth) << at;
      EXPECT_EQ(fact(g, "cbt_pool"), r.pool) << at;
      EXPECT_EQ(g.maxInstances, r.capacity) << at;
      EXPECT_EQ(g.initialState[LB_CBT_CAPACITY], r.capacity) << at;
      EXPECT_EQ(fact(g, "cbt_capacity"), r.capacity) << at;
      EXPECT_EQ(fact(g, "cbt_capacity_clamped"), 0) << at;
      EXPECT_EQ(g.capacityWord, LB_CBT_CAPACITY) << at;
      const uint32_t perDraw = kMaxVerticesPerDraw / 81;  // cbt-ts at subd 3
      EXPECT_EQ(g.maxDraws, std::string(scheme) == "cbt" ? 1u : (r.capacity + perDraw - 1) / perDraw) << at;
    }
  }
  // A larger viewport asks for more; the parameter replaces the rule, within the tree.
  EXPECT_EQ(cbtLod(16385, {}, {3840, 2160}).maxInstances, 1u << 18);
  EXPECT_EQ(cbtLod(16385, {{"pool", 262144}}, hd).maxInstances, 262144u);
  EXPECT_EQ(cbtLod(16385, {{"tri_size", 0.5}, {"pool", 131072}}, hd).maxInstances, 131072u);
  EXPECT_EQ(cbtLod(257, {{"pool", 1048576}}, hd).maxInstances, 2048u);
  // The device's most: 32 bytes a record in one storage buffer, 64 leaves a workgroup of one dispatch.
  GpuLod small = cbtLod(16385, {{"tri_size", 0.5}}, {1920, 1080, 32ull << 20});
  EXPECT_EQ(small.maxInstances, 1u << 20);
  EXPECT_EQ(fact(small, "cbt_pool"), 1u << 23);
  EXPECT_EQ(fact(small, "cbt_capacity_clamped"), 1);
  GpuLod dispatch = cbtLod(16385, {{"tri_size", 0.5}}, {1920, 1080, UINT64_MAX, 65535});
  EXPECT_EQ(dispatch.maxInstances, 65535u * 64u);
  EXPECT_EQ(fact(dispatch, "cbt_capacity_clamped"), 1);
}

// The deepest state: the H100's largest terrain, 32759^2 at cells_per_texel 2 (L = 16), fits at subd
// 3 (D = 27); at subd 2 the InputError names the fix.
TEST(CbtPool, TheLargestTerrainFitsAtSubd3AndADeeperTreeNamesTheFix) {
  const GpuLodBudget hd{1920, 1080};
  const GpuLod g = cbtLod(32759, {{"cells_per_texel", 2}, {"tri_size", 0.5}}, hd);
  EXPECT_EQ(fact(g, "cbt_depth"), 27);
  EXPECT_EQ(g.maxInstances, 1u << 23);
  EXPECT_EQ(fact(g, "cbt_state_bytes"), double((64u << 20) + LB_CBT_HEADER * 4));
  try {
    cbtLod(32759, {{"cells_per_texel", 2}, {"subd", 2}}, hd);
    ADD_FAILURE() << "depth 29 passed";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("depth 29"), std::string::npos) << what;
    EXPECT_NE(what.find("raise subd to 3 or lower cells_per_texel to 1 or less"), std::string::npos) << what;
  }
}

// A tiny pool overflows on the GPU and fails the replay (the batch pass counts the leaves past it and
// sizes no dispatch beyond it); the rule's pool does not, and a state claiming more room than the
// renderer holds is refused.
TEST_F(Cbt, ATinyPoolOverflowsAndTheRulesPoolDoesNot) {
  const Heightfield& hf = testTerrain();
  const CameraPose pose = overviewPose();
  Renderer tiny(gpu(), hf, {160, 90, 16}), ruled(gpu(), hf, {160, 90, 16});
  tiny.setScheme(cbtScheme(), {{"pool", 8}});
  ruled.setScheme(cbtScheme(), {});
  EXPECT_EQ(tiny.lodState().gpuLod().maxInstances, 8u);
  const std::vector<uint32_t> initial = ruled.lodState().read();
  EXPECT_EQ(ruled.lodState().gpuLod().maxInstances, std::min(1u << 17, 1u << initial[LB_CBT_DEPTH]));
  convergeLod(ruled, pose);
  EXPECT_EQ(ruled.lodState().overflow(), 0u);
  const std::vector<uint32_t> settled = ruled.lodState().read();
  ASSERT_GT(settled[LB_CBT_LEAVES], 8u);
  convergeLod(tiny, pose);
  const std::vector<uint32_t> st = tiny.lodState().read();
  EXPECT_GT(tiny.lodState().overflow(), 0u);
  EXPECT_EQ(st[LB_CBT_OVERFLOW], st[LB_CBT_LEAVES] - 8u);
  EXPECT_EQ(st[LB_CBT_DISPATCH], 1u) << "a dispatch past the capacity";
  tiny.lodState().snapshot();
  LodReplay replay(tiny, [&](int) { return pose; }, {});
  try {
    replay.advanceTo(0);
    ADD_FAILURE() << "the overflow passed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("LOD state overflow"), std::string::npos) << e.what();
  }
  EXPECT_THROW(tiny.lodState().load(settled), std::logic_error);
}

// converged_state_sha256 is the tree's (the leaf bitfield), not the header's: the terrain scaled by
// 4 (extent, heights and camera; exact in floats) converges to the same leaves while the header's
// height range differs, and the hash is equal. A tree one leaf apart hashes differently.
TEST_F(Cbt, ConvergedHashCoversTheTreeAloneNotTheHeader) {
  const Heightfield& hf = testTerrain();
  Heightfield big = hf;
  big.extent *= 4;
  for (float& h : big.h) h *= 4;
  big.updateRange();
  const CameraPose pose = firstPose("flyover.csv", hf);
  CameraPose bigPose = pose;
  bigPose.eye *= 4.0f, bigPose.target *= 4.0f;
  Renderer a(gpu(), hf, {160, 90, 16}), b(gpu(), big, {160, 90, 16});
  a.setScheme(cbtScheme(), {});
  b.setScheme(cbtScheme(), {});
  ConvergeResult ca = convergeLod(a, pose), cb = convergeLod(b, bigPose);
  const std::vector<uint32_t> sa = a.lodState().read(), sb = b.lodState().read();
  EXPECT_NE(sa[LB_CBT_MAX_HEIGHT], sb[LB_CBT_MAX_HEIGHT]) << "the headers must differ, or this proves nothing";
  ASSERT_EQ(cbt::leaves(sa), cbt::leaves(sb)) << "the scaled terrain must give the same tree";
  EXPECT_EQ(ca.stateSha256, cb.stateSha256);
  // Another tree (a finer target) hashes differently.
  a.setScheme(cbtScheme(), {{"tri_size", 4}});
  ConvergeResult fine = convergeLod(a, pose);
  EXPECT_NE(fine.instances, ca.instances);
  EXPECT_NE(fine.stateSha256, ca.stateSha256);
}
