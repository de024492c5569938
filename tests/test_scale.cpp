// Scale-free schemes (docs/design.md, What is measured): the same picture gives the same tessellation at
// any world scale. The procedural terrain with extent, heights and camera scaled by 0.01, 1 and 100
// (paths are relative to the extent) must give every scheme the same triangle counts on every
// frame; and on a real DEM at its own extent the distance-based schemes must neither collapse to
// their minimum level nor to one another's output.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <map>
#include <string>

#include "dem_crop.h"
#include "gpu_fixture.h"

using namespace lb;
using lbtest::gpu;

namespace {

struct Counts {
  uint64_t clip = 0, tes = 0;
};

Heightfield scaledTerrain(double scale) {
  TerrainSpec s;
  s.size = 129;
  s.seed = 7;
  s.extent = float(1000 * scale);
  s.heightScale = float(120 * scale);
  return makeProcedural(s);
}

CameraPath shippedPath(const std::string& name) {
  return loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + name + ".csv");
}

// Per frame: clipping invocations (triangles) and evaluation invocations.
std::vector<Counts> pathCounts(const Heightfield& hf, const Scheme& scheme, const RenderSettings& rs,
                               const std::string& pathName, int frames, const ParamValues& params = {}) {
  Renderer r(gpu(), hf, rs);
  r.setScheme(scheme, params);
  CameraPath path = shippedPath(pathName);
  const int total = frameCount(path, 30);
  std::vector<Counts> out;
  for (int k = 0; k < frames; ++k) {
    FrameResult fr = lbtest::renderOnce(r, samplePose(path, 30, k * (total - 1) / (frames - 1), hf));
    out.push_back({fr.stats.clipInvocations, fr.stats.tesInvocations});
  }
  return out;
}

// Small grids keep `reference` (level 64 everywhere) lavapipe-sized; sphere-rings gets two rings.
int gridFor(const Scheme& s) {
  if (s.info().name == "reference") return 2;
  if (s.info().name == "sphere-rings") return 64;
  return 16;
}

class ScaleFree : public lbtest::GpuTest, public ::testing::WithParamInterface<std::string> {};

}  // namespace

TEST_P(ScaleFree, SameTrianglesAtEveryWorldScale) {
  const Scheme& scheme = *findScheme(GetParam());
  if (!lbtest::drawsOnTestDevice(scheme))
    GTEST_SKIP() << "a mesh-shader scheme: the test device lacks VK_EXT_mesh_shader";
  const RenderSettings rs{160, 90, gridFor(scheme)};
  const Heightfield unit = scaledTerrain(1);
  // planefit's least-squares fit has its own scale-free unit (roughness in extents): both fits.
  std::vector<ParamValues> variants = {{}};
  if (GetParam() == "planefit") variants.push_back({{"fit", 1}, {"roughness", 0.004}});
  double worst = 0;  // largest relative triangle difference, printed for the record
  for (const ParamValues& params : variants)
    for (const char* path : {"flyover", "lowalt", "horizon"}) {
      const std::vector<Counts> base = pathCounts(unit, scheme, rs, path, 3, params);
      for (double scale : {0.01, 100.0}) {
        const std::vector<Counts> got = pathCounts(scaledTerrain(scale), scheme, rs, path, 3, params);
        for (size_t f = 0; f < base.size(); ++f) {
          SCOPED_TRACE(std::string(path) + " frame " + std::to_string(f) + " scale " + std::to_string(scale));
          EXPECT_GT(base[f].clip, 0u);
          worst = std::max(worst, std::abs(double(got[f].clip) - double(base[f].clip)) / double(base[f].clip));
          EXPECT_NEAR(double(got[f].clip), double(base[f].clip), 0.005 * double(base[f].clip)) << "triangles";
          EXPECT_NEAR(double(got[f].tes), double(base[f].tes), 0.005 * double(base[f].tes)) << "evaluations";
          // The instanced path selects on the CPU in double and places vertices on an integer
          // lattice: no tessellator rounding, so its counts must not move at all.
          if (scheme.info().path == DrawPath::InstancedGrid) EXPECT_EQ(got[f].clip, base[f].clip) << "triangles";
        }
      }
    }
  std::printf("[ScaleFree] %s: largest triangle difference at scale 0.01 or 100: %.4f%%\n", GetParam().c_str(),
              100 * worst);
}

INSTANTIATE_TEST_SUITE_P(Registry, ScaleFree, ::testing::ValuesIn([] {
                           std::vector<std::string> names;
                           for (const Scheme* s : allSchemes()) names.push_back(s->info().name);
                           return names;
                         }()),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

namespace {

// The committed SRTM crop (tests/dem_crop.h), loaded once.
const Heightfield* realDem() {
  static const Heightfield* hf = new Heightfield(loadHeightfield(lbtest::demCrop()));
  return hf;
}

constexpr int kDemWidth = 640, kDemHeight = 360;

class RealDem : public lbtest::GpuTest {};

}  // namespace

// The SRTM crop at 90 m spacing, height_scale 5 (the full tile at extent 108000 before): with world-unit distances
// every patch sat at min_lod and the three distance schemes drew the same triangles. At their defaults each now draws
// within 10x of sphere's screen-space LOD either way, and no two schemes give the same per-frame counters.
TEST_F(RealDem, DistanceSchemesStayWithinTenfoldOfSphereAndDiffer) {
  const Heightfield* hf = realDem();
  const RenderSettings rs{kDemWidth, kDemHeight, 32};
  const char* names[] = {"sphere", "distance", "interlock", "planefit"};
  for (const char* path : {"flyover", "lowalt"}) {
    SCOPED_TRACE(path);
    std::map<std::string, std::vector<Counts>> counts;
    for (const char* name : names) counts[name] = pathCounts(*hf, *findScheme(name), rs, path, 4);
    auto total = [&](const std::string& n) {
      double t = 0;
      for (const Counts& c : counts[n]) t += double(c.clip);
      return t;
    };
    for (const char* name : {"distance", "interlock", "planefit"}) {
      double ratio = total(name) / total("sphere");
      std::printf("[RealDem] %s %s: %.0f triangles over the frames, %.3fx sphere's\n", path, name, total(name), ratio);
      EXPECT_GE(ratio, 0.1) << name;
      EXPECT_LE(ratio, 10.0) << name;
    }
    for (size_t a = 0; a < std::size(names); ++a)
      for (size_t b = a + 1; b < std::size(names); ++b) {
        int same = 0;
        for (size_t f = 0; f < counts[names[a]].size(); ++f)
          same += counts[names[a]][f].clip == counts[names[b]][f].clip &&
                  counts[names[a]][f].tes == counts[names[b]][f].tes;
        EXPECT_EQ(same, 0) << names[a] << " and " << names[b] << " give identical counters on " << same << " frames";
      }
  }
}
