#include "vk/context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "error.h"
#include "vk/device_identity.h"
#include "vk/vk_check.h"

namespace lb {

std::atomic<int> vkFailCountdown{0};

const char* vkResultName(VkResult r) {
  // A table rather than a switch of macro cases: clang-format keeps it readable.
#define LB_NAME(x) \
  { x, #x }
  static const struct {
    VkResult result;
    const char* name;
  } kNames[] = {LB_NAME(VK_SUCCESS),
                LB_NAME(VK_NOT_READY),
                LB_NAME(VK_TIMEOUT),
                LB_NAME(VK_INCOMPLETE),
                LB_NAME(VK_ERROR_OUT_OF_HOST_MEMORY),
                LB_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY),
                LB_NAME(VK_ERROR_INITIALIZATION_FAILED),
                LB_NAME(VK_ERROR_DEVICE_LOST),
                LB_NAME(VK_ERROR_MEMORY_MAP_FAILED),
                LB_NAME(VK_ERROR_LAYER_NOT_PRESENT),
                LB_NAME(VK_ERROR_EXTENSION_NOT_PRESENT),
                LB_NAME(VK_ERROR_FEATURE_NOT_PRESENT),
                LB_NAME(VK_ERROR_INCOMPATIBLE_DRIVER),
                LB_NAME(VK_ERROR_TOO_MANY_OBJECTS),
                LB_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED),
                LB_NAME(VK_ERROR_UNKNOWN)};
#undef LB_NAME
  for (const auto& n : kNames)
    if (n.result == r) return n.name;
  return "VK_ERROR_(unnamed)";
}

void vkFail(VkResult r, const char* call, const char* file, int line) {
  char msg[512];
  std::snprintf(msg, sizeof msg, "%s:%d: %s failed with %s", file, line, call, vkResultName(r));
  throw std::runtime_error(msg);
}

std::string apiVersionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

std::string driverVersionString(const VkPhysicalDeviceProperties& p) {
  uint32_t v = p.driverVersion;
  if (p.vendorID == 0x10DE)  // NVIDIA packs 10.8.8.6 bits
    return std::to_string(v >> 22) + "." + std::to_string((v >> 14) & 0xff) + "." + std::to_string((v >> 6) & 0xff);
  return apiVersionString(v);
}

static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  auto* ctx = static_cast<Context*>(user);
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    ctx->validationErrors++;
    std::fprintf(stderr, "[validation error] %s\n", data->pMessage);
  } else if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    ctx->validationWarnings++;
    std::fprintf(stderr, "[validation warning] %s\n", data->pMessage);
  }
  return VK_FALSE;
}

static bool hasLayer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

static VkInstance makeInstance(bool validation, bool* debugUtils) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "lodbench";
  app.apiVersion = VK_API_VERSION_1_3;
  std::vector<const char*> layers, exts;
  if (validation) {
    layers.push_back("VK_LAYER_KHRONOS_validation");
    exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledLayerCount = uint32_t(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  ci.enabledExtensionCount = uint32_t(exts.size());
  ci.ppEnabledExtensionNames = exts.data();
  VkInstance instance = VK_NULL_HANDLE;
  VkResult r = vkCreateInstance(&ci, nullptr, &instance);
  if (r != VK_SUCCESS)
    throw std::runtime_error(std::string("vkCreateInstance failed (") + vkResultName(r) +
                             "): is a Vulkan driver installed? On Debian: apt-get install mesa-vulkan-drivers");
  *debugUtils = validation;
  return instance;
}

static int graphicsQueueFamily(VkPhysicalDevice pd) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
  std::vector<VkQueueFamilyProperties> fams(n);
  vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, fams.data());
  for (uint32_t i = 0; i < n; ++i)
    if ((fams[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (fams[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
        fams[i].timestampValidBits > 0)
      return int(i);
  return -1;
}

static std::vector<DeviceCandidate> examine(VkInstance instance, std::vector<VkPhysicalDevice>& out) {
  uint32_t n = 0;
  vkEnumeratePhysicalDevices(instance, &n, nullptr);
  out.resize(n);
  vkEnumeratePhysicalDevices(instance, &n, out.data());
  std::vector<DeviceCandidate> result;
  for (uint32_t i = 0; i < n; ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(out[i], &p);
    VkPhysicalDeviceFeatures f;
    vkGetPhysicalDeviceFeatures(out[i], &f);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f13};
    if (p.apiVersion >= VK_API_VERSION_1_3) vkGetPhysicalDeviceFeatures2(out[i], &f2);
    DeviceCandidate c{int(i), p.deviceName, false, "", deviceLimits(out[i])};
    c.cpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    c.mesh = meshShaderLimits(out[i]);
    if (p.apiVersion < VK_API_VERSION_1_3)
      c.rejectReason = "Vulkan " + apiVersionString(p.apiVersion) + " < 1.3 (needs dynamic rendering)";
    else if (!f.tessellationShader)
      c.rejectReason = "no tessellationShader feature";
    else if (!f.pipelineStatisticsQuery)
      c.rejectReason = "no pipelineStatisticsQuery feature (triangle counts)";
    else if (!f13.dynamicRendering)
      c.rejectReason = "no dynamicRendering feature";
    else if (!p.limits.timestampComputeAndGraphics)
      c.rejectReason = "timestamps not supported on graphics queues";
    else if (graphicsQueueFamily(out[i]) < 0)
      c.rejectReason = "no graphics+compute queue with timestamps";
    else if (p.limits.maxTessellationGenerationLevel < 64)
      c.rejectReason =
          "maxTessellationGenerationLevel " + std::to_string(p.limits.maxTessellationGenerationLevel) + " < 64";
    c.suitable = c.rejectReason.empty();
    result.push_back(c);
  }
  return result;
}

std::vector<DeviceCandidate> listDevices() {
  bool du = false;
  VkInstance inst = makeInstance(false, &du);
  std::vector<VkPhysicalDevice> pds;
  auto c = examine(inst, pds);
  vkDestroyInstance(inst, nullptr);
  return c;
}

static int choose(const std::vector<DeviceCandidate>& cands, const std::string& want, const std::string& where,
                  std::string& why) {
  auto lower = [](std::string s) {
    for (auto& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    return s;
  };
  bool isIndex = !want.empty() && want.find_first_not_of("0123456789") == std::string::npos;
  for (auto& c : cands) {
    bool match = want.empty() ? lower(c.name).find("llvmpipe") != std::string::npos
                 : isIndex    ? want.size() <= 9 && c.index == std::stoi(want)
                              : lower(c.name).find(lower(want)) != std::string::npos;
    if (match && c.suitable) return c.index;
  }
  if (want.empty())
    for (auto& c : cands)
      if (c.suitable) return c.index;
  why = want.empty()    ? "no suitable Vulkan device"
        : where.empty() ? "no suitable Vulkan device matches --device '" + want + "'"
                        : where + ": no suitable Vulkan device matches '" + want + "'";
  for (auto& c : cands)
    why += "\n  [" + std::to_string(c.index) + "] " + c.name + ": " + (c.suitable ? "suitable" : c.rejectReason);
  if (cands.empty()) why += " (no devices at all: apt-get install mesa-vulkan-drivers for lavapipe)";
  return -1;
}

// Validation asked for by the option or by LODBENCH_VALIDATION (set and not "0").
static bool validationRequested(const ContextOptions& options, std::string& how) {
  const char* env = std::getenv("LODBENCH_VALIDATION");
  how = options.validation ? "--validation" : env ? "LODBENCH_VALIDATION=" + std::string(env) : "";
  return options.validation || (env && std::strcmp(env, "0") != 0 && *env);
}

// Asked-for validation that silently turns itself off would let "zero validation messages"
// checks pass by comparing 0 with 0, so a missing layer is an error.
static void requireLayerIfAsked(const ContextOptions& options) {
  std::string how;
  if (validationRequested(options, how) && !hasLayer("VK_LAYER_KHRONOS_validation"))
    throw std::runtime_error("validation was requested (" + how +
                             ") but the layer VK_LAYER_KHRONOS_validation is not installed: "
                             "apt-get install vulkan-validationlayers (or bash scripts/install-deps.sh), "
                             "or unset LODBENCH_VALIDATION");
}

void checkContextOptions(const ContextOptions& options) {
  requireLayerIfAsked(options);
  if (options.device.empty()) return;
  std::string why;
  if (choose(listDevices(), options.device, options.deviceWhere, why) < 0) throw InputError(why);
}

void createContext(Context& ctx, const ContextOptions& options) {
  std::string how;
  const bool validation = validationRequested(options, how);
  requireLayerIfAsked(options);
  bool debugUtils = false;
  ctx.instance = makeInstance(validation, &debugUtils);
  ctx.validationEnabled = validation;
  if (debugUtils) {
    VkDebugUtilsMessengerCreateInfoEXT mi{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    mi.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT;
    mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    mi.pfnUserCallback = debugCallback;
    mi.pUserData = &ctx;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create) VK_CHECK(create(ctx.instance, &mi, nullptr, &ctx.messenger));
  }
  std::vector<VkPhysicalDevice> pds;
  ctx.candidates = examine(ctx.instance, pds);
  std::string why;
  int idx = choose(ctx.candidates, options.device, options.deviceWhere, why);
  if (idx < 0) {
    destroyContext(ctx);
    // A device the user named that does not exist is bad input; none at all is the machine's problem.
    if (!options.device.empty()) throw InputError(why);
    throw std::runtime_error(why);
  }
  ctx.physicalDevice = pds[size_t(idx)];
  vkGetPhysicalDeviceProperties(ctx.physicalDevice, &ctx.props);
  vkGetPhysicalDeviceMemoryProperties(ctx.physicalDevice, &ctx.memProps);
  VkPhysicalDeviceIDProperties ids{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
  VkPhysicalDeviceDriverProperties drv{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES, &ids};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &drv};
  vkGetPhysicalDeviceProperties2(ctx.physicalDevice, &p2);
  ctx.driverName = drv.driverName;
  ctx.driverInfo = drv.driverInfo;
  ctx.deviceUuid = formatUuid(ids.deviceUUID);
  ctx.driverUuid = formatUuid(ids.driverUUID);

  VkPhysicalDeviceFeatures have;
  vkGetPhysicalDeviceFeatures(ctx.physicalDevice, &have);
  ctx.enabledFeatures.tessellationShader = VK_TRUE;
  ctx.enabledFeatures.pipelineStatisticsQuery = VK_TRUE;
  ctx.enabledFeatures.fillModeNonSolid = have.fillModeNonSolid;                              // wireframe images only
  ctx.enabledFeatures.vertexPipelineStoresAndAtomics = have.vertexPipelineStoresAndAtomics;  // factor capture
  ctx.enabledFeatures.geometryShader = have.geometryShader;                                  // measurement passes only
  // GPU-indirect schemes that split their draw (cbt-ts): a count and first instances from the GPU.
  ctx.enabledFeatures.multiDrawIndirect = have.multiDrawIndirect;
  ctx.enabledFeatures.drawIndirectFirstInstance = have.drawIndirectFirstInstance;
  // The GPU ray-cast truth intersects in double where it can, as its CPU oracle does
  // (metrics/gpu_raycast.h), and GPU SSIM sums in double (metrics/gpu_reduce.h).
  ctx.enabledFeatures.shaderFloat64 = have.shaderFloat64;
  VkPhysicalDeviceVulkan12Features have12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 have2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &have12};
  vkGetPhysicalDeviceFeatures2(ctx.physicalDevice, &have2);
  ctx.drawIndirectCount = have12.drawIndirectCount;
  // Tests simulate a device without optional features (LODBENCH_TEST_DISABLE=geometryShader,...).
  if (const char* off = std::getenv("LODBENCH_TEST_DISABLE")) {
    std::string list = off;
    if (list.find("geometryShader") != std::string::npos) ctx.enabledFeatures.geometryShader = VK_FALSE;
    if (list.find("fillModeNonSolid") != std::string::npos) ctx.enabledFeatures.fillModeNonSolid = VK_FALSE;
    if (list.find("shaderFloat64") != std::string::npos) ctx.enabledFeatures.shaderFloat64 = VK_FALSE;
  }

  // Mesh shaders where the device has them; never a reason to reject a device.
  VkPhysicalDeviceMeshShaderFeaturesEXT mesh{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
  ctx.meshLimits = meshShaderLimits(ctx.physicalDevice);
  if (ctx.meshLimits.present) {
    VkPhysicalDeviceFeatures2 haveMesh{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &mesh};
    vkGetPhysicalDeviceFeatures2(ctx.physicalDevice, &haveMesh);
    ctx.meshShader = mesh.taskShader && mesh.meshShader;
    ctx.meshShaderQueries = ctx.meshShader && mesh.meshShaderQueries;
  }
  if (const char* off = std::getenv("LODBENCH_TEST_DISABLE"))
    if (std::string(off).find("meshShader") != std::string::npos) ctx.meshShader = ctx.meshShaderQueries = false;

  ctx.queueFamily = uint32_t(graphicsQueueFamily(ctx.physicalDevice));
  float prio = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = ctx.queueFamily;
  qi.queueCount = 1;
  qi.pQueuePriorities = &prio;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  f13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
  f12.hostQueryReset = VK_TRUE;
  f12.drawIndirectCount = ctx.drawIndirectCount;
  VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &f12};
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  di.pEnabledFeatures = &ctx.enabledFeatures;
  // Only the features the mesh path uses: the rest (multiview, primitive shading rate) stay off.
  VkPhysicalDeviceMeshShaderFeaturesEXT meshOn{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
  const char* meshExtension = VK_EXT_MESH_SHADER_EXTENSION_NAME;
  if (ctx.meshShader) {
    meshOn.taskShader = meshOn.meshShader = VK_TRUE;
    meshOn.meshShaderQueries = ctx.meshShaderQueries;
    f13.pNext = &meshOn;
    di.enabledExtensionCount = 1;
    di.ppEnabledExtensionNames = &meshExtension;
  }
  VK_CHECK(vkCreateDevice(ctx.physicalDevice, &di, nullptr, &ctx.device));
  vkGetDeviceQueue(ctx.device, ctx.queueFamily, 0, &ctx.queue);
  if (ctx.meshShader) {
    ctx.cmdDrawMeshTasks =
        reinterpret_cast<PFN_vkCmdDrawMeshTasksEXT>(vkGetDeviceProcAddr(ctx.device, "vkCmdDrawMeshTasksEXT"));
    ctx.cmdDrawMeshTasksIndirect = reinterpret_cast<PFN_vkCmdDrawMeshTasksIndirectEXT>(
        vkGetDeviceProcAddr(ctx.device, "vkCmdDrawMeshTasksIndirectEXT"));
    if (!ctx.cmdDrawMeshTasks || !ctx.cmdDrawMeshTasksIndirect) ctx.meshShader = ctx.meshShaderQueries = false;
  }
}

VkShaderStageFlags layoutStages(const Context& ctx) {
  VkShaderStageFlags s = VK_SHADER_STAGE_ALL_GRAPHICS | VK_SHADER_STAGE_COMPUTE_BIT;
  if (ctx.meshShader) s |= VK_SHADER_STAGE_TASK_BIT_EXT | VK_SHADER_STAGE_MESH_BIT_EXT;
  return s;
}

void destroyContext(Context& ctx) {
  if (ctx.device) {
    vkDeviceWaitIdle(ctx.device);
    ctx.keptTerrain.reset();
    vkDestroyDevice(ctx.device, nullptr);
  }
  if (ctx.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(ctx.instance, ctx.messenger, nullptr);
  }
  if (ctx.instance) vkDestroyInstance(ctx.instance, nullptr);
  ctx.device = VK_NULL_HANDLE;
  ctx.messenger = VK_NULL_HANDLE;
  ctx.instance = VK_NULL_HANDLE;
}

}  // namespace lb
