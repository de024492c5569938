// `lodbench devices` states each device's mesh-shader support (vk/mesh_shader_limits.h): the line
// for made-up devices, and the test device's line as the library reads it (lavapipe on Debian 12
// has no VK_EXT_mesh_shader, so CI sees "no").
#include <gtest/gtest.h>

#include "cli_run.h"
#include "gpu_fixture.h"
#include "schemes/preprocess/tess_patterns.h"
#include "vk/mesh_shader_limits.h"

using lb::MeshShaderLimits;

TEST(DevicesMeshShaders, LineNamesTheLimitsOrTheMissingExtension) {
  EXPECT_EQ(lb::meshShaderLine(MeshShaderLimits{}), "mesh shaders: no (VK_EXT_mesh_shader absent)");
  const MeshShaderLimits h100{true, 256, 256, 128, 32, 16384};
  EXPECT_EQ(lb::meshShaderLine(h100),
            "mesh shaders: yes (VK_EXT_mesh_shader: maxMeshOutputVertices 256, maxMeshOutputPrimitives 256, "
            "maxMeshWorkGroupInvocations 128, maxPreferredMeshWorkGroupInvocations 32, maxTaskPayloadSize 16384 "
            "bytes)");
}

// The command prints the library's line inside the test device's entry; where the extension is
// there, its limits hold the largest tessellation-pattern piece.
TEST(DevicesMeshShaders, DevicesCommandPrintsTheTestDevicesLine) {
  const MeshShaderLimits m = lb::meshShaderLimits(lbtest::gpu().physicalDevice);
  const std::string name = lbtest::gpu().props.deviceName;
  const lb::test::CliOut o = lb::test::lodbench("devices", false);
  ASSERT_EQ(o.code, 0) << o.text;
  const size_t entry = o.text.find(name);
  ASSERT_NE(entry, std::string::npos) << o.text;
  const size_t next = o.text.find("\n[", entry);
  const size_t line = o.text.find("    " + lb::meshShaderLine(m) + "\n", entry);
  ASSERT_NE(line, std::string::npos) << o.text;
  EXPECT_LT(line, next) << "the line belongs to " << name << "'s entry";
  if (!m.present) {
    EXPECT_EQ(m.maxOutputVertices, 0u) << "nothing is read without the extension";
    return;
  }
  EXPECT_GE(m.maxOutputVertices, uint32_t(lb::kMeshMinOutputVertices));
  EXPECT_GE(m.maxOutputPrimitives, uint32_t(lb::kMeshMinOutputPrimitives));
}
