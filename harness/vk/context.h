#pragma once
// Headless Vulkan: instance (optional validation layer), device chosen by name substring or
// index, one graphics+compute queue. No surface, no swapchain. The instance and device are the
// roots, created and destroyed here; every object made from the device is owned by a vk::Unique
// (vk/unique.h), which its owner must release before destroyContext.
#include <vulkan/vulkan.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "vk/device_limits.h"
#include "vk/mesh_shader_limits.h"

namespace lb {

struct ContextOptions {
  std::string device;       // "" = lavapipe if present else first suitable; digits = index
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation (also env LODBENCH_VALIDATION=1)
  // What named `device`, for the message when it matches no suitable device: "" = the --device
  // flag; else e.g. "c.json:3: field '/device'" (Config::deviceWhere).
  std::string deviceWhere;
};

struct DeviceCandidate {
  int index = 0;
  std::string name;
  bool suitable = false;
  std::string rejectReason;  // empty when suitable
  DeviceLimits limits;       // the largest terrain it takes (vk/device_limits.h)
  bool cpu = false;          // VK_PHYSICAL_DEVICE_TYPE_CPU: a software rasterizer such as lavapipe
  MeshShaderLimits mesh;     // what a mesh-shader path could use; not part of suitability
};

struct Context {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  VkPhysicalDeviceProperties props{};
  VkPhysicalDeviceMemoryProperties memProps{};
  VkPhysicalDeviceFeatures enabledFeatures{};
  bool drawIndirectCount = false;  // Vulkan 1.2 feature, enabled where the device has it
  // VK_EXT_mesh_shader with its taskShader and meshShader features, enabled where the device has
  // them (never required: a mesh-shader draw path is skipped without them), and meshShaderQueries
  // (task and mesh invocations in pipeline statistics). The draw commands are the extension's, so
  // they come from vkGetDeviceProcAddr (the loader exports core commands only).
  bool meshShader = false, meshShaderQueries = false;
  MeshShaderLimits meshLimits;
  PFN_vkCmdDrawMeshTasksEXT cmdDrawMeshTasks = nullptr;
  PFN_vkCmdDrawMeshTasksIndirectEXT cmdDrawMeshTasksIndirect = nullptr;
  std::string driverName, driverInfo;
  // VkPhysicalDeviceIDProperties, as vk/device_identity.h formats them: which board (two of one
  // model differ here) and which driver build.
  std::string deviceUuid, driverUuid;
  bool validationEnabled = false;
  std::vector<DeviceCandidate> candidates;
  // Count of validation messages of severity error (and warnings), for tests to assert zero.
  std::atomic<int> validationErrors{0};
  std::atomic<int> validationWarnings{0};
  // A large terrain's device copy kept between the renderers of one terrain
  // (render/device_terrain.h; typed there, so this layer need not know it). destroyContext
  // releases it before the device.
  std::shared_ptr<void> keptTerrain;
};

// Throws with every device's rejection reason when none fits: lb::InputError when options.device
// names no suitable device, std::runtime_error when there is none at all or when validation is
// asked for (option or LODBENCH_VALIDATION) and the layer is missing.
void createContext(Context& ctx, const ContextOptions& options);
// What createContext would refuse, checked without creating a device (cheap enough to call before
// creating any output): lb::InputError (every device's reason) when options.device names no
// suitable device, std::runtime_error when validation is asked for and the layer is missing.
void checkContextOptions(const ContextOptions& options);
void destroyContext(Context& ctx);
// The shader stages of the one pipeline layout every graphics and compute pipeline shares: all
// graphics stages, compute, and task and mesh where the device enables them.
VkShaderStageFlags layoutStages(const Context& ctx);
// Lists devices and whether each is suitable (creates and destroys its own instance).
std::vector<DeviceCandidate> listDevices();
std::string apiVersionString(uint32_t v);
std::string driverVersionString(const VkPhysicalDeviceProperties& props);

}  // namespace lb
