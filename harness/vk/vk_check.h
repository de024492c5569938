#pragma once
// VK_CHECK stays on in every build type: a benchmark that silently ignores a failed call lies.
#include <vulkan/vulkan.h>

#include <atomic>

namespace lb {
const char* vkResultName(VkResult r);
[[noreturn]] void vkFail(VkResult r, const char* call, const char* file, int line);

// Testing only: failNthVkCheck(n) makes the n-th VK_CHECK from now on fail without making its call
// (as a real failed create, which creates nothing), so tests can throw from every step of a
// creation and check that nothing is left behind. 0 turns it off. Off, a checked call costs one
// relaxed load of this counter.
extern std::atomic<int> vkFailCountdown;
inline void failNthVkCheck(int n) {
  vkFailCountdown.store(n);
}
// Checks still to go before the planted failure; 0 once it has fired (or when none is planted).
inline int vkChecksBeforeFailure() {
  return vkFailCountdown.load();
}
inline bool vkInjectedFailure() {
  return vkFailCountdown.load(std::memory_order_relaxed) > 0 && vkFailCountdown.fetch_sub(1) == 1;
}
}  // namespace lb

#define VK_CHECK(call)                                                                          \
  do {                                                                                          \
    VkResult vkCheckResult_ = lb::vkInjectedFailure() ? VK_ERROR_OUT_OF_DEVICE_MEMORY : (call); \
    if (vkCheckResult_ != VK_SUCCESS) lb::vkFail(vkCheckResult_, #call, __FILE__, __LINE__);    \
  } while (0)
