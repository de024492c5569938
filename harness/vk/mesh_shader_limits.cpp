#include "vk/mesh_shader_limits.h"

#include <cstring>
#include <vector>

namespace lb {

MeshShaderLimits meshShaderLimits(VkPhysicalDevice pd) {
  MeshShaderLimits m;
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  for (const VkExtensionProperties& e : exts)
    if (std::strcmp(e.extensionName, VK_EXT_MESH_SHADER_EXTENSION_NAME) == 0) m.present = true;
  if (!m.present) return m;
  VkPhysicalDeviceMeshShaderPropertiesEXT ms{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_PROPERTIES_EXT};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &ms};
  vkGetPhysicalDeviceProperties2(pd, &p2);
  m.maxOutputVertices = ms.maxMeshOutputVertices;
  m.maxOutputPrimitives = ms.maxMeshOutputPrimitives;
  m.maxWorkGroupInvocations = ms.maxMeshWorkGroupInvocations;
  m.maxPreferredWorkGroupInvocations = ms.maxPreferredMeshWorkGroupInvocations;
  m.maxTaskPayloadBytes = ms.maxTaskPayloadSize;
  m.maxTaskWorkGroupCountX = ms.maxTaskWorkGroupCount[0];
  m.maxTaskWorkGroupTotalCount = ms.maxTaskWorkGroupTotalCount;
  m.maxMeshWorkGroupCountX = ms.maxMeshWorkGroupCount[0];
  m.maxMeshWorkGroupTotalCount = ms.maxMeshWorkGroupTotalCount;
  return m;
}

std::string meshShaderLine(const MeshShaderLimits& m) {
  if (!m.present) return "mesh shaders: no (" VK_EXT_MESH_SHADER_EXTENSION_NAME " absent)";
  return "mesh shaders: yes (" VK_EXT_MESH_SHADER_EXTENSION_NAME ": maxMeshOutputVertices " +
         std::to_string(m.maxOutputVertices) + ", maxMeshOutputPrimitives " + std::to_string(m.maxOutputPrimitives) +
         ", maxMeshWorkGroupInvocations " + std::to_string(m.maxWorkGroupInvocations) +
         ", maxPreferredMeshWorkGroupInvocations " + std::to_string(m.maxPreferredWorkGroupInvocations) +
         ", maxTaskPayloadSize " + std::to_string(m.maxTaskPayloadBytes) + " bytes)";
}

}  // namespace lb
