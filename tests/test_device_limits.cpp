// Device limits for terrains (vk/device_limits.h): the arithmetic on made-up devices, and the real
// device's figures consistent with what `lodbench devices` prints.
#include <gtest/gtest.h>

#include "cli_run.h"
#include "gpu_fixture.h"
#include "vk/device_limits.h"

using lb::DeviceLimits;

namespace {

// A unified-memory device like lavapipe: one heap for images and staging.
DeviceLimits unified(uint64_t heapMiB, uint32_t maxDim = 16384) {
  DeviceLimits d;
  d.name = "unified";
  d.maxImageDimension2D = maxDim;
  d.maxAllocationBytes = 1ull << 40;
  d.deviceHeapBytes = d.stagingHeapBytes = heapMiB << 20;
  d.sharedHeap = true;
  return d;
}

}  // namespace

TEST(DeviceLimits, ImageDimensionBoundsEachSide) {
  const DeviceLimits d = unified(1 << 20);
  EXPECT_EQ(lb::terrainLimitProblem(d, 16384, 16384), "");
  EXPECT_NE(lb::terrainLimitProblem(d, 16385, 2).find("maxImageDimension2D of 16384"), std::string::npos);
  EXPECT_NE(lb::terrainLimitProblem(d, 2, 16385).find("maxImageDimension2D"), std::string::npos);
  EXPECT_EQ(lb::largestSquareTerrain(d), 16384);
}

TEST(DeviceLimits, OneHeapHoldsTwelveBytesASamplePlusTheReserve) {
  // 1 GiB heap: (1024 - 256) MiB / 12 bytes = 67,108,864 samples -> side 8192 exactly.
  const DeviceLimits d = unified(1024);
  EXPECT_EQ(lb::largestSquareTerrain(d), 8192);
  EXPECT_EQ(lb::terrainLimitProblem(d, 8192, 8192), "");
  const std::string p = lb::terrainLimitProblem(d, 8193, 8193);
  EXPECT_NE(p.find("memory heap"), std::string::npos) << p;
  EXPECT_NE(p.find("12 bytes a sample"), std::string::npos) << p;
}

TEST(DeviceLimits, SeparateHeapsNeedEightBytesOnTheDevice) {
  DeviceLimits d = unified(1024);
  d.sharedHeap = false;  // (1024 - 256) MiB / 8 bytes = 100,663,296 samples -> side 10,033
  d.stagingHeapBytes = 64ull << 30;
  EXPECT_EQ(lb::largestSquareTerrain(d), 10033);
  d.stagingHeapBytes = 256ull << 20;  // a 256 MiB staging heap holds 8192^2 x 4 bytes exactly
  EXPECT_EQ(lb::largestSquareTerrain(d), 8192);
  EXPECT_NE(lb::terrainLimitProblem(d, 8193, 8193).find("staging"), std::string::npos);
}

TEST(DeviceLimits, LargestAllocationBoundsOneImage) {
  DeviceLimits d = unified(1 << 20);
  d.maxAllocationBytes = 1ull << 30;  // 1 GiB / 4 bytes = 16384^2 samples
  EXPECT_EQ(lb::largestSquareTerrain(d), 16384);
  d.maxAllocationBytes = (1ull << 30) - 1;
  EXPECT_EQ(lb::largestSquareTerrain(d), 16383);
  EXPECT_NE(lb::terrainLimitProblem(d, 16384, 16384).find("maxMemoryAllocationSize"), std::string::npos);
}

TEST(DeviceLimits, TheTestDeviceTakesTheCommittedCropAndStatesItsLargest) {
  const DeviceLimits d = lb::deviceLimits(lbtest::gpu().physicalDevice);
  EXPECT_GT(d.maxImageDimension2D, 0u);
  EXPECT_GT(d.deviceHeapBytes, 0u);
  EXPECT_EQ(lb::terrainLimitProblem(d, 601, 601), "");
  const int side = lb::largestSquareTerrain(d);
  EXPECT_LE(uint32_t(side), d.maxImageDimension2D);
  EXPECT_EQ(lb::terrainLimitProblem(d, side, side), "");
  if (uint32_t(side) < d.maxImageDimension2D) EXPECT_NE(lb::terrainLimitProblem(d, side + 1, side + 1), "");
  std::printf("[device limits] %s: largest terrain %d^2 (maxImageDimension2D %u, heap %llu MiB, %s)\n", d.name.c_str(),
              side, d.maxImageDimension2D, (unsigned long long)(d.deviceHeapBytes >> 20),
              d.sharedHeap ? "one heap" : "separate heaps");
}

// `lodbench devices` states the same largest terrain as the library computes for the test device.
TEST(DeviceLimits, DevicesCommandPrintsTheLargestTerrain) {
  const DeviceLimits d = lb::deviceLimits(lbtest::gpu().physicalDevice);
  const std::string side = std::to_string(lb::largestSquareTerrain(d));
  const lb::test::CliOut o = lb::test::lodbench("devices", false);
  ASSERT_EQ(o.code, 0) << o.text;
  EXPECT_NE(o.text.find(d.name), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("largest terrain: " + side + " x " + side + " samples"), std::string::npos) << o.text;
}
