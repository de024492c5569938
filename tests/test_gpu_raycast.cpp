// The GPU ray-cast truth (harness/metrics/gpu_raycast.h) against its CPU oracle
// (metrics/raycast.h raycastImage) on every shipped camera path, on synthetic terrains, the
// committed real DEM crop and extents of 10 m and 10,000 km; a planted defect (the pyramid one level
// short) and a pose nudged by one pixel show that the comparison sees a wrong image.
#include <cmath>
#include <cstdio>
#include <string>

#include "dem_crop.h"
#include "error.h"
#include "gpu_fixture.h"
#include "metrics/gpu_raycast.h"
#include "metrics/raycast.h"
#include "shaders/raycast_params.h"
#include "terrain/generators.h"

using namespace lb;

namespace {

constexpr int kW = 160, kH = 90;
constexpr double kDistanceTolerance = 1e-5;  // relative

// What differs between the oracle's frame and the GPU's.
struct Diff {
  int pixels = 0, cpuHits = 0;
  int coverage = 0;      // terrain in one image, sky in the other
  int rgb = 0;           // terrain in both, colours differ
  int worstChannel = 0;  // the largest difference of one channel where both show terrain
  int distance = 0;      // terrain in both, distances differ by more than kDistanceTolerance relative
  double worstRelative = 0;
  void add(const Diff& o) {
    pixels += o.pixels, cpuHits += o.cpuHits, coverage += o.coverage, rgb += o.rgb, distance += o.distance;
    worstRelative = std::max(worstRelative, o.worstRelative);
    worstChannel = std::max(worstChannel, o.worstChannel);
  }
};

Diff compare(const RgbaImage& cpu, const std::vector<float>& cpuDist, const RgbaImage& gpu,
             const std::vector<float>& gpuDist) {
  Diff d;
  d.pixels = cpu.width * cpu.height;
  for (size_t i = 0; i < size_t(d.pixels); ++i) {
    const bool a = cpuDist[i] >= 0, b = gpuDist[i] >= 0;
    d.cpuHits += a;
    if (a != b) {
      ++d.coverage;
      continue;
    }
    if (!a) continue;
    int channel = 0;
    for (size_t c = 0; c < 3; ++c)
      channel = std::max(channel, std::abs(int(cpu.px[i * 4 + c]) - int(gpu.px[i * 4 + c])));
    d.rgb += channel > 0;
    d.worstChannel = std::max(d.worstChannel, channel);
    const double rel = std::fabs(double(gpuDist[i]) - double(cpuDist[i])) / double(cpuDist[i]);
    d.worstRelative = std::max(d.worstRelative, rel);
    d.distance += rel > kDistanceTolerance;
  }
  return d;
}

Diff compareFrame(GpuRaycast& gpu, const Heightfield& hf, const CameraPose& pose) {
  std::vector<float> cpuDist, gpuDist;
  const RgbaImage cpu = raycastImage(hf, pose, kW, kH, &cpuDist, 2);
  const RgbaImage img = gpu.image(pose, kW, kH, &gpuDist);
  return compare(cpu, cpuDist, img, gpuDist);
}

// Frames 0, 1/3, 2/3 and the last of every shipped path (configs/paths), each against the oracle.
Diff everyShippedPath(GpuRaycast& gpu, const Heightfield& hf, const char* label) {
  Diff all;
  for (const std::string& file : lbtest::shippedPathFiles()) {
    const CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + file);
    const int frames = frameCount(path, 30);
    for (int f : {0, frames / 3, 2 * frames / 3, frames - 1}) {
      const Diff d = compareFrame(gpu, hf, samplePose(path, 30, f, hf));
      EXPECT_EQ(d.coverage, 0) << label << " " << file << " frame " << f;
      all.add(d);
    }
  }
  std::printf("[gpu raycast] %s (%s): %d pixels, %d terrain; coverage %d, rgb %d, distance > 1e-5: %d (worst %.2e)\n",
              label, gpu.usesDouble() ? "double" : "float", all.pixels, all.cpuHits, all.coverage, all.rgb,
              all.distance, all.worstRelative);
  return all;
}

Heightfield procedural(float extent, float heightScale) {
  TerrainSpec s;
  s.size = 129;
  s.seed = 7;
  s.extent = extent;
  s.heightScale = heightScale;
  return makeProcedural(s);
}

// The oracle's own answer: with double on both sides, every pixel agrees; on a CPU device (lavapipe,
// IEEE division and square root, no contraction) every distance to the last bit.
void expectExact(const Diff& d) {
  EXPECT_GT(d.cpuHits, d.pixels / 4);  // the views show terrain, not only sky
  EXPECT_EQ(d.coverage, 0);
  EXPECT_EQ(d.rgb, 0);
  EXPECT_EQ(d.distance, 0);
  if (lbtest::gpu().props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) EXPECT_EQ(d.worstRelative, 0.0);
}

}  // namespace

class GpuRaycastTest : public lbtest::GpuTest {};

TEST_F(GpuRaycastTest, UsesDoubleWhereTheDeviceHasIt) {
  GpuRaycast gpu(lbtest::gpu(), lbtest::testTerrain());
  EXPECT_EQ(gpu.usesDouble(), bool(lbtest::gpu().enabledFeatures.shaderFloat64));
  GpuRaycast f32(lbtest::gpu(), lbtest::testTerrain(), {.allowDouble = false});
  EXPECT_FALSE(f32.usesDouble());
}

TEST_F(GpuRaycastTest, MatchesTheOracleOnEveryShippedPathOverProceduralTerrain) {
  const Heightfield& hf = lbtest::testTerrain();
  GpuRaycast gpu(lbtest::gpu(), hf);
  expectExact(everyShippedPath(gpu, hf, "procedural 129, 1 km"));
}

TEST_F(GpuRaycastTest, MatchesTheOracleOnSpikesAndCliff) {
  for (const char* type : {"spikes", "cliff"}) {
    TerrainSpec s;
    s.type = type;
    s.size = 257;
    s.extent = 1000;
    s.heightScale = 120;
    const Heightfield hf = makeGeneratedTerrain(s);
    GpuRaycast gpu(lbtest::gpu(), hf);
    expectExact(everyShippedPath(gpu, hf, type));
  }
}

TEST_F(GpuRaycastTest, MatchesTheOracleOnTheRealDemCrop) {
  const Heightfield hf = makeHeightfield(lbtest::demCrop());
  GpuRaycast gpu(lbtest::gpu(), hf);
  expectExact(everyShippedPath(gpu, hf, "DEM crop 601, 54 km"));
}

TEST_F(GpuRaycastTest, MatchesTheOracleAtTenMetresAndTenThousandKilometres) {
  for (float extent : {10.0f, 1e7f}) {
    const Heightfield hf = procedural(extent, extent * 0.01f);  // 1% relief: 0.1 m and 100 km peaks
    GpuRaycast gpu(lbtest::gpu(), hf);
    expectExact(everyShippedPath(gpu, hf, extent < 100 ? "procedural, 10 m" : "procedural, 10,000 km"));
  }
}

// The pyramid one level short: its root covers only the first quadrant of the terrain, so every
// ray that would hit elsewhere misses.
TEST_F(GpuRaycastTest, PlantedShortPyramidIsCaught) {
  const Heightfield& hf = lbtest::testTerrain();
  GpuRaycast broken(lbtest::gpu(), hf, {.testDropLevels = 1});
  const Diff d = compareFrame(broken, hf, lbtest::overviewPose());
  std::printf("[gpu raycast] pyramid one level short: %d of %d terrain pixels lost\n", d.coverage, d.cpuHits);
  EXPECT_GT(d.coverage, d.cpuHits / 4);
}

// The comparison is sensitive to one pixel: the GPU's view of a pose turned by about one pixel
// differs from the oracle's of the original pose.
TEST_F(GpuRaycastTest, PoseNudgedByOnePixelDiffers) {
  const Heightfield& hf = lbtest::testTerrain();
  GpuRaycast gpu(lbtest::gpu(), hf);
  const CameraPose pose = lbtest::overviewPose();
  CameraPose nudged = pose;
  // One pixel of a 60-degree, 90-pixel-high view is 2 tan(30 deg) / 90 of the target distance.
  const glm::vec3 toTarget = pose.target - pose.eye;
  nudged.target += glm::vec3(0, glm::length(toTarget) * 2 * std::tan(glm::radians(30.0f)) / float(kH), 0);
  std::vector<float> cpuDist, gpuDist;
  const RgbaImage cpu = raycastImage(hf, pose, kW, kH, &cpuDist, 2);
  const RgbaImage img = gpu.image(nudged, kW, kH, &gpuDist);
  const Diff d = compare(cpu, cpuDist, img, gpuDist);
  std::printf("[gpu raycast] nudged one pixel: coverage %d, rgb %d, distance %d of %d pixels\n", d.coverage, d.rgb,
              d.distance, d.pixels);
  EXPECT_GT(d.coverage, 0);
  EXPECT_GT(d.rgb, d.pixels / 10);
  EXPECT_GT(d.distance, d.pixels / 10);
}

// Without distances the colours are the same; with a buffer too small, a clear error and no dispatch.
TEST_F(GpuRaycastTest, DistanceIsOptionalAndBufferSizesAreChecked) {
  const Heightfield& hf = lbtest::testTerrain();
  GpuRaycast gpu(lbtest::gpu(), hf);
  std::vector<float> dist;
  const RgbaImage with = gpu.image(lbtest::overviewPose(), kW, kH, &dist);
  const RgbaImage without = gpu.image(lbtest::overviewPose(), kW, kH);
  EXPECT_EQ(with.px, without.px);
  Buffer small = createBuffer(lbtest::gpu(), 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  try {
    gpu.run(lbtest::overviewPose(), kW, kH, small, nullptr);
    ADD_FAILURE() << "no error for a 4-byte buffer";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("57600 bytes"), std::string::npos) << e.what();
  }
}

// Float (devices without shaderFloat64), with the ray made in double on the host. Measured on
// lavapipe: no pixel changes between terrain and sky; colours move by one level on 1-5 pixels of
// the procedural terrains (any extent) and 102 of the DEM crop's 412,731; distances beyond 1e-5
// relative on 0.2% of terrain pixels (worst 6.4e-5), on the crop 8.4% (worst 2.9e-4): its cell
// coordinates keep about 2^-24 of the extent, 1/600 of a cell of 90 m, under low views.
TEST_F(GpuRaycastTest, FloatFallbackStaysNearTheOracle) {
  std::vector<Heightfield> terrains;
  for (float extent : {10.0f, 1000.0f, 1e7f}) terrains.push_back(procedural(extent, extent * 0.01f));
  terrains.push_back(makeHeightfield(lbtest::demCrop()));
  for (const Heightfield& hf : terrains) {
    GpuRaycast gpu(lbtest::gpu(), hf, {.allowDouble = false});
    Diff all;
    for (const std::string& file : lbtest::shippedPathFiles()) {
      const CameraPath path = loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/" + file);
      const int frames = frameCount(path, 30);
      for (int f : {0, frames / 3, 2 * frames / 3, frames - 1})
        all.add(compareFrame(gpu, hf, samplePose(path, 30, f, hf)));
    }
    std::printf(
        "[gpu raycast] float, extent %g: %d pixels, %d terrain; coverage %d, rgb %d (worst channel %d), "
        "distance > 1e-5: %d (worst %.2e)\n",
        double(hf.extent), all.pixels, all.cpuHits, all.coverage, all.rgb, all.worstChannel, all.distance,
        all.worstRelative);
    EXPECT_FALSE(gpu.usesDouble());
    EXPECT_EQ(all.coverage, 0);
    EXPECT_LE(all.rgb, all.cpuHits / 2000);
    EXPECT_LE(all.worstChannel, 1);
    EXPECT_LE(all.distance, all.cpuHits / 10);
    EXPECT_LT(all.worstRelative, 1e-3);
  }
}

// The shader's stack packs a node's column in 14 bits: a wider terrain is refused with its size
// named (FeatureMissing: the case is recorded as skipped with the reason), never cast wrong.
TEST_F(GpuRaycastTest, TerrainBeyondTheShaderLimitIsRefused) {
  Heightfield hf;
  hf.width = LB_RAYCAST_MAX_CELLS + 2;  // one cell too many
  hf.height = 2;
  hf.h.assign(size_t(hf.width) * size_t(hf.height), 0.0f);
  try {
    GpuRaycast gpu(lbtest::gpu(), hf);
    ADD_FAILURE() << "no error for " << hf.width << " samples a row";
  } catch (const FeatureMissing& e) {
    EXPECT_NE(std::string(e.what()).find("32770 x 2 samples"), std::string::npos) << e.what();
  }
}
