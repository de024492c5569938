// Every registered scheme: builds, renders the shipped paths without validation errors, repeats
// its counters exactly, keeps every factor in [1, 64] (or 0 = culled; none on the instanced path),
// rejects bad parameters.
#include <cmath>
#include <set>

#include "error.h"
#include "gpu_fixture.h"
#include "replay/lod_replay.h"
#include "shaders/shared.h"

using namespace lb;

namespace {

std::vector<std::string> schemeNamesList() {
  std::vector<std::string> names;
  for (const Scheme* s : allSchemes()) names.push_back(s->info().name);
  return names;
}

std::string paramName(const ::testing::TestParamInfo<std::string>& info) {
  std::string n = info.param;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

class EveryScheme : public lbtest::GpuTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(EveryScheme, RendersShippedPathsDeterministicallyWithinLimits) {
  const Scheme& scheme = *findScheme(GetParam());
  if (!lbtest::drawsOnTestDevice(scheme))
    GTEST_SKIP() << "a mesh-shader scheme: the test device lacks VK_EXT_mesh_shader";
  const Heightfield& terrain = lbtest::testTerrain();
  Renderer r(lbtest::gpu(), terrain, {96, 64, 12});
  r.setScheme(scheme, {});
  for (const char* name : {"flyover", "lowalt", "horizon"}) {
    CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name + ".csv");
    int frames = frameCount(path, 30);
    for (int f : {0, frames / 2, frames - 1}) {
      CameraPose pose = samplePose(path, 30, f, terrain);
      // A stateful scheme refines its tree a little every frame: at the pose's fixed point first.
      if (r.statefulLod()) EXPECT_TRUE(convergeLod(r, pose).converged);
      FrameResult a = lbtest::renderOnce(r, pose);
      FrameResult b = lbtest::renderOnce(r, pose);
      SCOPED_TRACE(std::string(name) + " frame " + std::to_string(f));
      EXPECT_EQ(a.stats.tcsPatches, b.stats.tcsPatches);
      EXPECT_EQ(a.stats.tesInvocations, b.stats.tesInvocations);
      EXPECT_EQ(a.stats.clipInvocations, b.stats.clipInvocations);
      EXPECT_EQ(a.stats.clipPrimitives, b.stats.clipPrimitives);
      EXPECT_EQ(a.stats.fsInvocations, b.stats.fsInvocations);
      // 0 on the instanced and mesh paths; a GPU-indirect patch footprint (cbt-ts) tessellates every instance.
      const bool patchInstances = r.path() == DrawPath::GpuIndirect && !scheme.info().tesc.empty();
      EXPECT_EQ(a.stats.tcsPatches, patchInstances ? a.instances : r.path() == DrawPath::Mesh ? 0 : r.patchCount());
      EXPECT_EQ(a.instances, b.instances);
      EXPECT_EQ(a.draws, b.draws);
      if (r.path() == DrawPath::InstancedGrid) {
        EXPECT_GT(a.instances, 0u);
        EXPECT_EQ(a.stats.clipInvocations, a.stats.iaPrimitives) << "no tessellation: one primitive a triangle";
      }
      EXPECT_GT(a.stats.clipInvocations, 0u) << "the terrain is in view on every shipped path";
      r.renderImage(pose, pose, RenderMode::Shaded);
      auto levels = r.capturedLevels();
      int outOfRange = 0;
      for (float v : levels) outOfRange += !(v == 0.0f || (v >= 1.0f && v <= LB_MAX_FACTOR));
      EXPECT_EQ(outOfRange, 0);
    }
  }
}

TEST_P(EveryScheme, RejectsOutOfRangeParameters) {
  const SchemeInfo& info = findScheme(GetParam())->info();
  EXPECT_NO_THROW(resolveParams(info, {}));
  for (const ParamSpec& p : info.params) {
    for (double bad : {p.min - 1.0, p.max + 1.0, double(NAN)}) {
      try {
        resolveParams(info, {{p.name, bad}});
        ADD_FAILURE() << p.name << " = " << bad << " accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(p.name), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(info.name), std::string::npos) << e.what();
      }
    }
    EXPECT_NO_THROW(resolveParams(info, {{p.name, p.defaultValue}}));
  }
  EXPECT_THROW(resolveParams(info, {{"no_such_parameter", 1.0}}), InputError);
}

// Parameters reach the shaders through named slots (shaders/<scheme>_params.h), never by list order.
TEST_P(EveryScheme, ParameterSlotsAreDistinctAndInRange) {
  const SchemeInfo& info = findScheme(GetParam())->info();
  std::set<int> slots;
  for (const ParamSpec& p : info.params) {
    EXPECT_GE(p.slot, 0) << p.name;
    EXPECT_LT(p.slot, LB_SCHEME_PARAM_VEC4S * 4) << p.name;
    EXPECT_TRUE(slots.insert(p.slot).second) << p.name << " shares slot " << p.slot;
  }
}

// A parameter lands in its slot whatever its position in the list.
TEST_P(EveryScheme, UpdatePacksEachParameterAtItsSlot) {
  const Scheme& s = *findScheme(GetParam());
  ParamValues values = resolveParams(s.info(), {});
  FrameUniforms u{};
  for (size_t i = 0; i < s.info().params.size(); ++i) values[s.info().params[i].name] = 0.125 * double(i + 1);
  s.update(u, values);
  for (const ParamSpec& p : s.info().params)
    EXPECT_EQ(u.params[p.slot / 4][p.slot % 4], float(values[p.name])) << p.name;
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryScheme, ::testing::ValuesIn(schemeNamesList()), paramName);

TEST(Registry, NamesAreUniqueAndDescribed) {
  std::set<std::string> names;
  for (const Scheme* s : allSchemes()) {
    const SchemeInfo& i = s->info();
    EXPECT_TRUE(names.insert(i.name).second) << i.name;
    EXPECT_FALSE(i.description.empty()) << i.name;
    EXPECT_FALSE(i.seed.empty()) << i.name;
    // Each path's LOD shader: the control shader, the instanced path's vertex shader, or the mesh path's
    // task and mesh shaders.
    const std::string& lod = i.path == DrawPath::Tessellation ? i.tesc : i.path == DrawPath::Mesh ? i.mesh : i.vert;
    EXPECT_FALSE(lod.empty()) << i.name;
    if (i.path == DrawPath::Mesh) EXPECT_FALSE(i.task.empty()) << i.name;
    EXPECT_LE(i.params.size(), size_t(LB_SCHEME_PARAM_VEC4S * 4)) << i.name;
  }
}

}  // namespace
