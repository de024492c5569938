// A large terrain's device copy (render/device_terrain.h) is kept between the renderers of that
// terrain: the second renderer draws the same pixels as a first one built alone, and the
// device holds one copy, which each renderer still counts as its own in summary.memory.
#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "render/device_terrain.h"
#include "terrain/terrain_cache.h"
#include "vk/gpu_memory.h"

namespace lb {
namespace {

using lbtest::gpu;

class DeviceTerrainTest : public lbtest::GpuTest {};

TerrainSpec largeSpec(uint32_t seed) {
  TerrainSpec spec;
  spec.size = 2049;  // past kKeptTerrainSamples: the terrain cache keeps it
  spec.seed = seed;
  spec.extent = 2048;
  spec.heightScale = 300;
  return spec;
}

uint64_t liveTerrainBytes() {
  return gpuBytesLive(GpuResource::Heights) + gpuBytesLive(GpuResource::NormalMap);
}

TEST_F(DeviceTerrainTest, RenderersOfTheKeptTerrainShareOneCopyAndDrawTheSame) {
  const Scheme& scheme = *findScheme("cdlod");
  const CameraPose pose = lbtest::poseAt({-200, 500, -200}, {1024, 0, 1024});
  const uint64_t before = liveTerrainBytes();
  std::shared_ptr<const Heightfield> hf = sharedHeightfield(largeSpec(5));
  ASSERT_EQ(keptHeightfield(*hf), hf);
  std::vector<uint8_t> first, second;
  uint64_t oneCopy = 0;
  {
    Renderer a(gpu(), *hf, {96, 64, 8});
    a.setScheme(scheme, {});
    first = a.renderImage(pose, pose, RenderMode::Shaded);
    oneCopy = liveTerrainBytes() - before;
    EXPECT_GT(a.setupCosts().pagesS, 0.0);
    EXPECT_EQ(a.gpuMemory().bytes(GpuResource::Heights) + a.gpuMemory().bytes(GpuResource::NormalMap), oneCopy);
  }
  EXPECT_EQ(liveTerrainBytes() - before, oneCopy) << "the copy outlives its first renderer";
  {
    Renderer b(gpu(), *hf, {96, 64, 8});
    Renderer c(gpu(), *hf, {96, 64, 8});
    EXPECT_EQ(b.setupCosts().pagesS, 0.0) << "the kept copy was cut and uploaded again";
    EXPECT_EQ(liveTerrainBytes() - before, oneCopy) << "three renderers, more than one copy";
    b.setScheme(scheme, {});
    second = b.renderImage(pose, pose, RenderMode::Shaded);
    EXPECT_EQ(b.gpuMemory().bytes(GpuResource::Heights) + b.gpuMemory().bytes(GpuResource::NormalMap), oneCopy);
  }
  EXPECT_EQ(first, second);
  // A test's option is never shared: a copy of its own, released with its renderer.
  {
    RenderSettings own{96, 64, 8};
    own.testPageLayers = 1;
    Renderer d(gpu(), *hf, own);
    EXPECT_GT(d.setupCosts().pagesS, 0.0);
    EXPECT_GT(liveTerrainBytes() - before, oneCopy);
  }
  EXPECT_EQ(liveTerrainBytes() - before, oneCopy);
  // Another terrain replaces the kept one, on the host and on the device: one copy, not two.
  hf.reset();
  std::shared_ptr<const Heightfield> other = sharedHeightfield(largeSpec(6));
  {
    Renderer e(gpu(), *other, {96, 64, 8});
    EXPECT_GT(e.setupCosts().pagesS, 0.0);
    EXPECT_EQ(liveTerrainBytes() - before, oneCopy);
  }
  // The context lets its copy go with the device (destroyContext); the test context lives on, so
  // the test lets it go here and checks that everything came back.
  gpu().keptTerrain.reset();
  EXPECT_EQ(liveTerrainBytes(), before);
}

}  // namespace
}  // namespace lb
