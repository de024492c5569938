#pragma once
// Whether a device can take a mesh-shader draw path (VK_EXT_mesh_shader), and the limits such a
// path is sized by: a workgroup's output vertices and primitives bound one tessellation pattern
// piece (schemes/preprocess/tess_patterns.h), its invocations the threads that emit them, the task
// payload what a task shader hands its mesh workgroups. Read only where the extension is listed:
// chaining its properties struct for a device without it is invalid usage.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

namespace lb {

struct MeshShaderLimits {
  bool present = false;                  // VK_EXT_mesh_shader among the device's extensions; the rest is 0 without it
  uint32_t maxOutputVertices = 0;        // maxMeshOutputVertices
  uint32_t maxOutputPrimitives = 0;      // maxMeshOutputPrimitives
  uint32_t maxWorkGroupInvocations = 0;  // maxMeshWorkGroupInvocations
  uint32_t maxPreferredWorkGroupInvocations = 0;  // maxPreferredMeshWorkGroupInvocations
  uint32_t maxTaskPayloadBytes = 0;               // maxTaskPayloadSize
  // How many workgroups one draw may launch: task workgroups along x and in all (a draw's task
  // grid), mesh workgroups one task workgroup may emit along x and in all.
  uint32_t maxTaskWorkGroupCountX = 0, maxTaskWorkGroupTotalCount = 0;
  uint32_t maxMeshWorkGroupCountX = 0, maxMeshWorkGroupTotalCount = 0;
};

MeshShaderLimits meshShaderLimits(VkPhysicalDevice pd);
// One line for `lodbench devices`: "mesh shaders: yes (...)" with the limits under their Vulkan
// names, or "mesh shaders: no (VK_EXT_mesh_shader absent)".
std::string meshShaderLine(const MeshShaderLimits& m);

}  // namespace lb
