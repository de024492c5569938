// The only place that destroys device objects (see vk/unique.h).
#include "vk/unique.h"

#include <atomic>

namespace lb::vk {

namespace {
std::atomic<int> live{0};
}

int liveObjects() {
  return live.load();
}
void countObject(int delta) {
  live.fetch_add(delta, std::memory_order_relaxed);
}

void destroy(VkDevice d, VkBuffer h) {
  vkDestroyBuffer(d, h, nullptr);
}
void destroy(VkDevice d, VkDeviceMemory h) {
  vkFreeMemory(d, h, nullptr);
}
void destroy(VkDevice d, VkImage h) {
  vkDestroyImage(d, h, nullptr);
}
void destroy(VkDevice d, VkImageView h) {
  vkDestroyImageView(d, h, nullptr);
}
void destroy(VkDevice d, VkSampler h) {
  vkDestroySampler(d, h, nullptr);
}
void destroy(VkDevice d, VkDescriptorSetLayout h) {
  vkDestroyDescriptorSetLayout(d, h, nullptr);
}
void destroy(VkDevice d, VkDescriptorPool h) {
  vkDestroyDescriptorPool(d, h, nullptr);
}
void destroy(VkDevice d, VkPipelineLayout h) {
  vkDestroyPipelineLayout(d, h, nullptr);
}
void destroy(VkDevice d, VkPipeline h) {
  vkDestroyPipeline(d, h, nullptr);
}
void destroy(VkDevice d, VkShaderModule h) {
  vkDestroyShaderModule(d, h, nullptr);
}
void destroy(VkDevice d, VkFence h) {
  vkDestroyFence(d, h, nullptr);
}
void destroy(VkDevice d, VkCommandPool h) {
  vkDestroyCommandPool(d, h, nullptr);
}
void destroy(VkDevice d, VkQueryPool h) {
  vkDestroyQueryPool(d, h, nullptr);
}

}  // namespace lb::vk
