#pragma once
// Plain structs over Vulkan objects with createX/destroyX pairs.
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

namespace lb {

struct Context;

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers stay mapped
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
};

// hostVisible: HOST_VISIBLE|COHERENT and mapped; otherwise DEVICE_LOCAL.
void createBuffer(Context& ctx, Buffer& b, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);
void destroyBuffer(Context& ctx, Buffer& b);
// Device-local buffer filled through a staging copy.
void createBufferWithData(Context& ctx, Buffer& b, const void* data, VkDeviceSize size, VkBufferUsageFlags usage);

void createImage(Context& ctx, Image& img, uint32_t w, uint32_t h, VkFormat format, VkImageUsageFlags usage,
                 VkImageAspectFlags aspect);
void destroyImage(Context& ctx, Image& img);
// Uploads tightly packed texels and leaves the image in SHADER_READ_ONLY_OPTIMAL.
void uploadImage(Context& ctx, Image& img, const void* data, VkDeviceSize bytes);

// Records with `record`, submits, waits. For set-up work only, never inside timed frames.
void runOneShot(Context& ctx, const std::function<void(VkCommandBuffer)>& record);

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess);

// A global memory dependency (e.g. shader or copy writes before host reads).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

VkShaderModule loadShaderModule(Context& ctx, const std::string& name);  // name relative to the SPIR-V dir
std::string shaderDir();  // LODBENCH_SHADER_DIR env override, else the build's directory

}  // namespace lb
