#pragma once
// Shared GPU test fixture: one Vulkan context (lavapipe by default, validation layer on when
// LODBENCH_VALIDATION=1, as ctest sets it) and a check that no test causes a validation error.
#include <gtest/gtest.h>

#include "camera/camera_path.h"
#include "render/renderer.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "vk/context.h"

namespace lbtest {

lb::Context& gpu();
// Procedural test terrain (deterministic), default 129^2 samples over extent 1000, peak 120.
const lb::Heightfield& testTerrain();
// A pose looking at the terrain from above one corner.
lb::CameraPose overviewPose();
lb::CameraPose poseAt(glm::vec3 eye, glm::vec3 target, float fov = 60.0f);

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override { errorsBefore_ = gpu().validationErrors.load(); }
  void TearDown() override {
    EXPECT_EQ(gpu().validationErrors.load(), errorsBefore_) << "Vulkan validation errors during this test";
  }
  int errorsBefore_ = 0;
};

// Whether the test device draws the scheme: every scheme, but a mesh-shader one (DrawPath::Mesh)
// only where the device has VK_EXT_mesh_shader (elsewhere its case is skipped, and its test).
bool drawsOnTestDevice(const lb::Scheme& scheme);
// The registry's schemes the test device draws, in registry order.
std::vector<const lb::Scheme*> drawableSchemes();

// File names of every shipped camera path (configs/paths/*.csv), sorted: "dive.csv", ...
std::vector<std::string> shippedPathFiles();

// Renders one frame synchronously and returns its statistics.
lb::FrameResult renderOnce(lb::Renderer& r, const lb::CameraPose& pose);

}  // namespace lbtest
