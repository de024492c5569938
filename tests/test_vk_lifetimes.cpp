// Failure injection: every checked Vulkan call of each multi-object creation is made to fail in
// turn (lb::failNthVkCheck, vk/vk_check.h). Whatever the step, the creation must throw and release
// everything it made: vk::Unique's count of live objects comes back to where it was, and the
// validation layer (on under ctest) reports no object left alive when the test's own device is
// destroyed. The same creation must then run as if nothing had happened, with the same output.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <vector>

#include "gpu_fixture.h"
#include "render/compute_pass.h"
#include "render/height_pages.h"
#include "render/probe.h"
#include "shaders/shared.h"
#include "vk/resources.h"
#include "vk/unique.h"
#include "vk/vk_check.h"

namespace {

using Output = std::vector<uint8_t>;

template <typename T>
Output bytesOf(const std::vector<T>& v) {
  Output out(v.size() * sizeof(T));
  std::memcpy(out.data(), v.data(), out.size());
  return out;
}

// Its own device, so that what a test leaks is reported (at vkDestroyDevice) within the test.
class VkLifetimes : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* dev = std::getenv("LODBENCH_TEST_DEVICE");
    lb::createContext(ctx_, {dev ? dev : "", false});
  }
  void TearDown() override {
    lb::failNthVkCheck(0);
    lb::destroyContext(ctx_);
    EXPECT_EQ(ctx_.validationErrors.load(), 0) << "validation errors, objects left at vkDestroyDevice included";
  }

  // Runs `create` with its n-th checked Vulkan call failing, n = 1, 2, ... until a run reaches its
  // end before the planted failure; returns how many steps failed. Every failed run must throw
  // and leave no object alive; the run that reaches its end must return `expected`.
  int failEveryStep(const std::function<Output()>& create, const Output& expected) {
    const int live = lb::vk::liveObjects();
    for (int n = 1; n <= 5000; ++n) {
      lb::failNthVkCheck(n);
      bool threw = false;
      Output out;
      try {
        out = create();
      } catch (const std::runtime_error&) {
        threw = true;
      }
      const bool fired = lb::vkChecksBeforeFailure() == 0;
      lb::failNthVkCheck(0);
      EXPECT_EQ(lb::vk::liveObjects(), live) << "objects left after failing checked call " << n;
      if (!fired) {
        EXPECT_FALSE(threw) << "the run without a failure threw";
        EXPECT_TRUE(out == expected) << "the run after " << n - 1 << " failed ones differs from the reference";
        return n - 1;
      }
      EXPECT_TRUE(threw) << "checked call " << n << " failed without an exception";
    }
    ADD_FAILURE() << "the creation never reached its end";
    return 0;
  }

  Output renderOnce(const std::string& scheme) {
    lb::Renderer r(ctx_, lbtest::testTerrain(), {64, 48, 8});
    r.setScheme(*lb::findScheme(scheme), {});
    const lb::CameraPose pose = lbtest::overviewPose();
    return r.renderImage(pose, pose, lb::RenderMode::Shaded);
  }

  lb::Context ctx_;
};

TEST_F(VkLifetimes, ValidationReportsAnObjectLeftAtDeviceDestruction) {
  // What the tests below rely on: a leak is counted as a validation error.
  if (!ctx_.validationEnabled) GTEST_SKIP() << "validation layer off (LODBENCH_VALIDATION=1 turns it on)";
  lb::Context leaky;
  const char* dev = std::getenv("LODBENCH_TEST_DEVICE");
  lb::createContext(leaky, {dev ? dev : "", false});
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  VkSampler leaked;
  ASSERT_EQ(vkCreateSampler(leaky.device, &si, nullptr, &leaked), VK_SUCCESS);
  std::fprintf(stderr, "[lodbench tests] a validation error about a VkSampler not destroyed is expected here\n");
  lb::destroyContext(leaky);
  EXPECT_GT(leaky.validationErrors.load(), 0);
}

TEST_F(VkLifetimes, RendererOfATessellationSchemeReleasesEverythingAtEveryFailedStep) {
  const Output reference = renderOnce("distance");
  const int steps = failEveryStep([&] { return renderOnce("distance"); }, reference);
  std::printf("renderer (distance): %d checked calls failed in turn\n", steps);
  EXPECT_GT(steps, 50);
}

TEST_F(VkLifetimes, RendererOfAComputePassSchemeReleasesEverythingAtEveryFailedStep) {
  const Output reference = renderOnce("planefit");
  const int steps = failEveryStep([&] { return renderOnce("planefit"); }, reference);
  std::printf("renderer (planefit): %d checked calls failed in turn\n", steps);
  EXPECT_GT(steps, 50);
}

TEST_F(VkLifetimes, ComputePassReleasesEverythingAtEveryFailedStep) {
  const lb::Heightfield& terrain = lbtest::testTerrain();
  const lb::HeightPages height = lb::createHeightPages(ctx_, terrain, {});
  lb::vk::Unique<VkSampler> sampler = lb::createSampler(ctx_, VK_FILTER_NEAREST);
  lb::Image output =
      lb::createImage(ctx_, 8, 8, VK_FORMAT_R32G32B32A32_SFLOAT,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT);
  lb::ComputePush push{};
  push.terrain = glm::vec4(terrain.extent, 8.0f, terrain.minHeight, terrain.maxHeight);
  auto pass = [&] {
    lb::runComputePass(ctx_, "planefit", sampler, height, output, push);
    return bytesOf(lb::readImageRgba32f(ctx_, output));
  };
  const Output reference = pass();
  const int steps = failEveryStep(pass, reference);
  std::printf("compute pass (planefit): %d checked calls failed in turn\n", steps);
  EXPECT_GT(steps, 10);
}

TEST_F(VkLifetimes, ProbeReleasesEverythingAtEveryFailedStep) {
  lb::ProbeOptions o;
  o.width = 64;
  o.height = 48;
  o.grid = 8;
  o.level = 4;
  o.warmup = 1;
  o.frames = 2;
  auto probe = [&] {
    lb::ProbeResult p = lb::runProbe(ctx_, lbtest::testTerrain(), lbtest::overviewPose(), o);
    const lb::PipelineStats& s = p.stats;
    return bytesOf(std::vector<uint64_t>{s.iaVertices, s.vsInvocations, s.tcsPatches, s.tesInvocations,
                                         s.clipPrimitives, s.fsInvocations, p.draws});
  };
  const Output reference = probe();
  const int steps = failEveryStep(probe, reference);
  std::printf("probe: %d checked calls failed in turn\n", steps);
  EXPECT_GT(steps, 30);
}

}  // namespace
