#pragma once
// VK_CHECK stays on in every build type: a benchmark that silently ignores a failed call lies.
#include <vulkan/vulkan.h>

namespace lb {
const char* vkResultName(VkResult r);
[[noreturn]] void vkFail(VkResult r, const char* call, const char* file, int line);
}  // namespace lb

#define VK_CHECK(call)                                                  \
  do {                                                                  \
    VkResult vkCheckResult_ = (call);                                   \
    if (vkCheckResult_ != VK_SUCCESS) lb::vkFail(vkCheckResult_, #call, __FILE__, __LINE__); \
  } while (0)
