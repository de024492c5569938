#pragma once
// The one owner of every Vulkan object a device creates: a move-only handle that destroys its
// object when it goes out of scope. Members of this type are released by the compiler in reverse
// order when a constructor throws half-way, so a failed creation leaves nothing behind and no
// class needs a hand-written clean-up path. Command buffers and descriptor sets are not owned one
// by one: they go back with the pool they came from, which is owned here.
//
// Usage: create into a local, then hand it over (a failed create leaves its output undefined):
//   VkSampler raw;
//   VK_CHECK(vkCreateSampler(device, &info, nullptr, &raw));
//   sampler_ = vk::Unique(device, raw);
#include <vulkan/vulkan.h>

#include <utility>

namespace lb::vk {

// Non-dispatchable handles are distinct pointer types only on 64-bit targets; on 32-bit ones they
// are all uint64_t and the destroy() overloads below would collide.
static_assert(sizeof(void*) == 8, "vk::Unique tells handle types apart by type: 64-bit targets only");

void destroy(VkDevice d, VkBuffer h);
void destroy(VkDevice d, VkDeviceMemory h);
void destroy(VkDevice d, VkImage h);
void destroy(VkDevice d, VkImageView h);
void destroy(VkDevice d, VkSampler h);
void destroy(VkDevice d, VkDescriptorSetLayout h);
void destroy(VkDevice d, VkDescriptorPool h);
void destroy(VkDevice d, VkPipelineLayout h);
void destroy(VkDevice d, VkPipeline h);
void destroy(VkDevice d, VkShaderModule h);
void destroy(VkDevice d, VkFence h);
void destroy(VkDevice d, VkCommandPool h);
void destroy(VkDevice d, VkQueryPool h);

// Objects owned by a Unique right now, over all devices: a test creates and fails creations and
// checks that this comes back to where it started.
int liveObjects();
void countObject(int delta);

template <typename T>
class Unique {
 public:
  Unique() = default;
  Unique(VkDevice device, T handle) : device_(device), handle_(handle) {
    if (handle_) countObject(1);
  }
  ~Unique() { reset(); }
  Unique(Unique&& o) noexcept : device_(o.device_), handle_(std::exchange(o.handle_, T(VK_NULL_HANDLE))) {}
  Unique& operator=(Unique&& o) noexcept {
    if (this != &o) {
      reset();
      device_ = o.device_;
      handle_ = std::exchange(o.handle_, T(VK_NULL_HANDLE));
    }
    return *this;
  }
  Unique(const Unique&) = delete;
  Unique& operator=(const Unique&) = delete;

  void reset() {
    if (!handle_) return;
    destroy(device_, handle_);
    handle_ = VK_NULL_HANDLE;
    countObject(-1);
  }
  T get() const { return handle_; }
  // Where Vulkan wants an array of one handle (pSetLayouts, pBuffers).
  const T* ptr() const { return &handle_; }
  // Only from a living owner: converting a temporary would hand out a handle it destroys at once.
  operator T() const& { return handle_; }
  operator T() const&& = delete;
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  T handle_ = VK_NULL_HANDLE;
};

}  // namespace lb::vk
