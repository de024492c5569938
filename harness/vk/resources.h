#pragma once
// Buffers and images as owners of their Vulkan objects (vk/unique.h): move-only, released when
// they go out of scope or are assigned {}.
#include <vulkan/vulkan.h>

#include <functional>
#include <string>
#include <vector>

#include "vk/gpu_memory.h"
#include "vk/unique.h"

namespace lb {

struct Context;

// Members in creation order, so the object is released before the memory bound to it. `charge`
// holds the allocation's bytes against its tag (vk/gpu_memory.h) while the memory lives.
struct Buffer {
  MemoryCharge charge;
  vk::Unique<VkDeviceMemory> memory;
  vk::Unique<VkBuffer> buffer;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers stay mapped (freeing the memory unmaps it)
};

struct Image {
  MemoryCharge charge;
  vk::Unique<VkDeviceMemory> memory;
  vk::Unique<VkImage> image;
  vk::Unique<VkImageView> view;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
  uint32_t mipLevels = 1;
  uint32_t layers = 1;
};

// hostVisible: HOST_VISIBLE|COHERENT and mapped; otherwise DEVICE_LOCAL. Every helper charges the
// allocation to `tag` (vk/gpu_memory.h): what it holds and whose it is. A host-visible buffer the
// device can only copy into (usage TRANSFER_DST alone) is a read-back, made as createReadBackBuffer.
Buffer createBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible, MemoryTag tag = {});
// Host-visible and mapped, for the host to read what the device wrote (captures, read-backs):
// HOST_CACHED too where the device has such a type, since the host reads write-combined memory
// uncached (on a discrete GPU, tens of times slower); the same type as createBuffer's otherwise.
Buffer createReadBackBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryTag tag = {});
// Device-local buffer filled through a staging copy (the staging charged as Staging to tag's account).
Buffer createBufferWithData(Context& ctx, const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                            MemoryTag tag = {});
// The same from parts laid end to end, copied straight into the staging buffer: no host array of
// the whole (the ray cast's pyramid and normal map levels, gigabytes at 16385^2).
struct BufferPart {
  const void* data;
  VkDeviceSize bytes;
};
Buffer createBufferWithParts(Context& ctx, const std::vector<BufferPart>& parts, VkBufferUsageFlags usage,
                             MemoryTag tag = {});

// mipLevels > 1: a full or partial mip chain; the view covers every level.
Image createImage(Context& ctx, uint32_t w, uint32_t h, VkFormat format, VkImageUsageFlags usage,
                  VkImageAspectFlags aspect, MemoryTag tag = {}, uint32_t mipLevels = 1);
// A 2D array image of `layers` layers, one level, its view VK_IMAGE_VIEW_TYPE_2D_ARRAY (even of one
// layer: the heightfield's pages, render/height_pages.h). Left in UNDEFINED layout.
Image createImageArray(Context& ctx, uint32_t w, uint32_t h, uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                       MemoryTag tag = {});
// Uploads tightly packed texels of level 0 and leaves the image in SHADER_READ_ONLY_OPTIMAL.
void uploadImage(Context& ctx, const Image& img, const void* data, VkDeviceSize bytes);
// Every level's tightly packed texels, level 0 first (level k: max(1, size >> k) a side).
struct ImageLevelData {
  const void* data;
  VkDeviceSize bytes;
};
void uploadImageLevels(Context& ctx, const Image& img, const std::vector<ImageLevelData>& levels);

// Nearest-filtered (or linear) sampler clamped to the edge; maxLod > 0: mip levels up to maxLod,
// mixed linearly (trilinear with VK_FILTER_LINEAR).
vk::Unique<VkSampler> createSampler(Context& ctx, VkFilter filter, float maxLod = 0.0f);
// A pool of resettable command buffers on the context's queue family, and `count` of them
// (released with the pool).
vk::Unique<VkCommandPool> createCommandPool(Context& ctx, VkCommandBuffer* buffers, uint32_t count);
vk::Unique<VkFence> createFence(Context& ctx);
// A descriptor set layout, a pool holding one set of it, that set and a pipeline layout with one
// push-constant range (none when pushBytes is 0): what the renderer, the probe and a compute pass each bind.
struct DescriptorBinding {
  uint32_t binding;
  VkDescriptorType type;
  VkShaderStageFlags stages;
  uint32_t count = 1;  // descriptors of the binding (a descriptor array when more than 1)
};
struct Bindings {
  vk::Unique<VkDescriptorSetLayout> setLayout;
  vk::Unique<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;  // released with the pool
  vk::Unique<VkPipelineLayout> pipelineLayout;
};
Bindings createBindings(Context& ctx, const std::vector<DescriptorBinding>& bindings, VkShaderStageFlags pushStages,
                        uint32_t pushBytes);

// Records with `record`, submits, waits. For set-up work only, never inside timed frames.
void runOneShot(Context& ctx, const std::function<void(VkCommandBuffer)>& record);

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess);

// A global memory dependency (e.g. shader or copy writes before host reads).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// A shader by its SPIR-V file name ("sphere.tesc.spv"): a plugin's (addSpirv) or from shaderDir().
vk::Unique<VkShaderModule> loadShaderModule(Context& ctx, const std::string& name);
// LODBENCH_SHADER_DIR where set; else share/lodbench/spirv beside an installed binary's bin/; else
// the build's directory.
std::string shaderDir();
// SPIR-V that lives in a plugin's library, not in shaderDir(), under the name loadShaderModule is
// asked for. Called while plugins load, before any renderer exists. Throws on a name taken twice.
void addSpirv(const std::string& name, const unsigned char* bytes, size_t size);
// The name is a plugin's shader or a file in shaderDir().
bool spirvExists(const std::string& name);

}  // namespace lb
