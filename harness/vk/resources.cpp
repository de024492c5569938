#include "vk/resources.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "vk/context.h"
#include "vk/vk_check.h"

namespace lb {

// The first type of `bits` with `want`, else `fallback`.
static uint32_t preferMemoryType(Context& ctx, uint32_t bits, VkMemoryPropertyFlags want, uint32_t fallback) {
  for (uint32_t i = 0; i < ctx.memProps.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (ctx.memProps.memoryTypes[i].propertyFlags & want) == want) return i;
  return fallback;
}

static uint32_t findMemoryType(Context& ctx, uint32_t bits, VkMemoryPropertyFlags want) {
  const uint32_t i = preferMemoryType(ctx, bits, want, UINT32_MAX);
  if (i == UINT32_MAX) throw std::runtime_error("no Vulkan memory type with the required properties");
  return i;
}

static constexpr VkMemoryPropertyFlags kHost =
    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;

static Buffer makeBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible, bool readBack,
                         MemoryTag tag) {
  Buffer b;
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size;
  bi.usage = usage;
  VkBuffer buffer;
  VK_CHECK(vkCreateBuffer(ctx.device, &bi, nullptr, &buffer));
  b.buffer = vk::Unique(ctx.device, buffer);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, buffer, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = findMemoryType(ctx, req.memoryTypeBits,
                                      hostVisible ? kHost : VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT));
  // A read-back is read by the host: cached memory where the device has it (the first HOST_VISIBLE
  // type of a discrete GPU is write-combined, which the host reads uncached).
  if (hostVisible && (readBack || usage == VK_BUFFER_USAGE_TRANSFER_DST_BIT))
    ai.memoryTypeIndex =
        preferMemoryType(ctx, req.memoryTypeBits, kHost | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, ai.memoryTypeIndex);
  VkDeviceMemory memory;
  VK_CHECK(vkAllocateMemory(ctx.device, &ai, nullptr, &memory));
  b.memory = vk::Unique(ctx.device, memory);
  b.charge = MemoryCharge(tag, req.size);
  VK_CHECK(vkBindBufferMemory(ctx.device, buffer, memory, 0));
  b.size = size;
  if (hostVisible) VK_CHECK(vkMapMemory(ctx.device, memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  return b;
}

Buffer createBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible, MemoryTag tag) {
  return makeBuffer(ctx, size, usage, hostVisible, false, tag);
}

Buffer createReadBackBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryTag tag) {
  return makeBuffer(ctx, size, usage, true, true, tag);
}

Buffer createBufferWithData(Context& ctx, const void* data, VkDeviceSize size, VkBufferUsageFlags usage,
                            MemoryTag tag) {
  return createBufferWithParts(ctx, {{data, size}}, usage, tag);
}

Buffer createBufferWithParts(Context& ctx, const std::vector<BufferPart>& parts, VkBufferUsageFlags usage,
                             MemoryTag tag) {
  VkDeviceSize size = 0;
  for (const BufferPart& p : parts) size += p.bytes;
  Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, {GpuResource::Staging, tag.account});
  VkDeviceSize at = 0;
  for (const BufferPart& p : parts) {
    if (p.bytes) std::memcpy(static_cast<char*>(staging.mapped) + at, p.data, size_t(p.bytes));
    at += p.bytes;
  }
  Buffer b = createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false, tag);
  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, size};
    vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &region);
  });
  return b;
}

namespace {

// A device-local 2D image of `layers` layers and `mipLevels` levels with one view over all of them:
// the one creation path of createImage and createImageArray.
Image createImageLayers(Context& ctx, uint32_t w, uint32_t h, uint32_t layers, uint32_t mipLevels,
                        VkImageViewType viewType, VkFormat format, VkImageUsageFlags usage, VkImageAspectFlags aspect,
                        MemoryTag tag) {
  Image img;
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = format;
  ii.extent = {w, h, 1};
  ii.mipLevels = mipLevels;
  ii.arrayLayers = layers;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = usage;
  ii.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage image;
  VK_CHECK(vkCreateImage(ctx.device, &ii, nullptr, &image));
  img.image = vk::Unique(ctx.device, image);
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device, image, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = findMemoryType(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkDeviceMemory memory;
  VK_CHECK(vkAllocateMemory(ctx.device, &ai, nullptr, &memory));
  img.memory = vk::Unique(ctx.device, memory);
  img.charge = MemoryCharge(tag, req.size);
  VK_CHECK(vkBindImageMemory(ctx.device, image, memory, 0));
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image;
  vi.viewType = viewType;
  vi.format = format;
  vi.subresourceRange = {aspect, 0, mipLevels, 0, layers};
  VkImageView view;
  VK_CHECK(vkCreateImageView(ctx.device, &vi, nullptr, &view));
  img.view = vk::Unique(ctx.device, view);
  img.format = format;
  img.width = w;
  img.height = h;
  img.mipLevels = mipLevels;
  img.layers = layers;
  return img;
}

}  // namespace

Image createImage(Context& ctx, uint32_t w, uint32_t h, VkFormat format, VkImageUsageFlags usage,
                  VkImageAspectFlags aspect, MemoryTag tag, uint32_t mipLevels) {
  return createImageLayers(ctx, w, h, 1, mipLevels, VK_IMAGE_VIEW_TYPE_2D, format, usage, aspect, tag);
}

Image createImageArray(Context& ctx, uint32_t w, uint32_t h, uint32_t layers, VkFormat format, VkImageUsageFlags usage,
                       MemoryTag tag) {
  return createImageLayers(ctx, w, h, layers, 1, VK_IMAGE_VIEW_TYPE_2D_ARRAY, format, usage, VK_IMAGE_ASPECT_COLOR_BIT,
                           tag);
}

void uploadImage(Context& ctx, const Image& img, const void* data, VkDeviceSize bytes) {
  uploadImageLevels(ctx, img, {{data, bytes}});
}

void uploadImageLevels(Context& ctx, const Image& img, const std::vector<ImageLevelData>& levels) {
  VkDeviceSize total = 0;
  for (const ImageLevelData& l : levels) total += (l.bytes + 15) & ~VkDeviceSize(15);  // copy offsets 16-aligned
  Buffer staging = createBuffer(ctx, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true, {GpuResource::Staging});
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  for (size_t k = 0; k < levels.size(); ++k) {
    std::memcpy(static_cast<char*>(staging.mapped) + offset, levels[k].data, size_t(levels[k].bytes));
    VkBufferImageCopy region{};
    region.bufferOffset = offset;
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, uint32_t(k), 0, 1};
    region.imageExtent = {std::max(1u, img.width >> k), std::max(1u, img.height >> k), 1};
    regions.push_back(region);
    offset += (levels[k].bytes + 15) & ~VkDeviceSize(15);
  }
  runOneShot(ctx, [&](VkCommandBuffer cmd) {
    imageBarrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           uint32_t(regions.size()), regions.data());
    imageBarrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_READ_BIT);
  });
}

vk::Unique<VkSampler> createSampler(Context& ctx, VkFilter filter, float maxLod) {
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = filter;
  si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  si.maxLod = maxLod;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler;
  VK_CHECK(vkCreateSampler(ctx.device, &si, nullptr, &sampler));
  return vk::Unique(ctx.device, sampler);
}

vk::Unique<VkCommandPool> createCommandPool(Context& ctx, VkCommandBuffer* buffers, uint32_t count) {
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = ctx.queueFamily;
  VkCommandPool raw;
  VK_CHECK(vkCreateCommandPool(ctx.device, &pi, nullptr, &raw));
  vk::Unique pool(ctx.device, raw);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = raw;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = count;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &ai, buffers));
  return pool;
}

vk::Unique<VkFence> createFence(Context& ctx) {
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  VK_CHECK(vkCreateFence(ctx.device, &fi, nullptr, &fence));
  return vk::Unique(ctx.device, fence);
}

Bindings createBindings(Context& ctx, const std::vector<DescriptorBinding>& bindings, VkShaderStageFlags pushStages,
                        uint32_t pushBytes) {
  Bindings out;
  std::vector<VkDescriptorSetLayoutBinding> b;
  std::vector<VkDescriptorPoolSize> sizes;
  for (const DescriptorBinding& d : bindings) {
    b.push_back({d.binding, d.type, d.count, d.stages, nullptr});
    auto same =
        std::find_if(sizes.begin(), sizes.end(), [&](const VkDescriptorPoolSize& s) { return s.type == d.type; });
    if (same == sizes.end())
      sizes.push_back({d.type, d.count});
    else
      same->descriptorCount += d.count;
  }
  VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  li.bindingCount = uint32_t(b.size());
  li.pBindings = b.data();
  VkDescriptorSetLayout setLayout;
  VK_CHECK(vkCreateDescriptorSetLayout(ctx.device, &li, nullptr, &setLayout));
  out.setLayout = vk::Unique(ctx.device, setLayout);
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = 1;
  pi.poolSizeCount = uint32_t(sizes.size());
  pi.pPoolSizes = sizes.data();
  VkDescriptorPool pool;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &pi, nullptr, &pool));
  out.pool = vk::Unique(ctx.device, pool);
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &setLayout;
  VK_CHECK(vkAllocateDescriptorSets(ctx.device, &ai, &out.set));
  VkPushConstantRange pc{pushStages, 0, pushBytes};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &setLayout;
  pli.pushConstantRangeCount = pushBytes > 0 ? 1 : 0;  // a pass with no push constants has no range
  pli.pPushConstantRanges = &pc;
  VkPipelineLayout layout;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pli, nullptr, &layout));
  out.pipelineLayout = vk::Unique(ctx.device, layout);
  return out;
}

void runOneShot(Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
  // Its own transient pool: the command buffer goes back with it on every exit.
  VkCommandBuffer cmd;
  vk::Unique<VkCommandPool> pool = createCommandPool(ctx, &cmd, 1);
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  vk::Unique<VkFence> fence = createFence(ctx);
  VK_CHECK(vkQueueSubmit(ctx.queue, 1, &si, fence));
  try {
    VK_CHECK(vkWaitForFences(ctx.device, 1, fence.ptr(), VK_TRUE, UINT64_MAX));
  } catch (...) {
    // The work may still run: it must end before the pool, the fence and the caller's staging go.
    vkQueueWaitIdle(ctx.queue);
    throw;
  }
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout from, VkImageLayout to,
                  VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess, VkPipelineStageFlags2 dstStage,
                  VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  // Every level of an image with mips, every layer of an array (the heightfield's pages).
  b.subresourceRange = {aspect, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.imageMemoryBarrierCount = 1;
  di.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &di);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = srcStage;
  mb.srcAccessMask = srcAccess;
  mb.dstStageMask = dstStage;
  mb.dstAccessMask = dstAccess;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &di);
}

static std::map<std::string, std::vector<uint32_t>>& pluginSpirv() {
  static std::map<std::string, std::vector<uint32_t>> table;
  return table;
}

std::string shaderDir() {
  const char* env = std::getenv("LODBENCH_SHADER_DIR");
  if (env && *env) return env;
  // An installed binary (cmake --install) finds its SPIR-V beside it, not in the build tree it came from.
  static const std::string installed = [] {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return std::string();
    const std::filesystem::path dir = exe.parent_path().parent_path() / "share/lodbench/spirv";
    return std::filesystem::exists(dir / "terrain.vert.spv", ec) ? dir.string() : std::string();
  }();
  return installed.empty() ? LODBENCH_SHADER_DIR : installed;
}

void addSpirv(const std::string& name, const unsigned char* bytes, size_t size) {
  if (size == 0 || size % 4 != 0) throw std::runtime_error("SPIR-V '" + name + "' is not a whole number of words");
  std::vector<uint32_t> words(size / 4);
  std::memcpy(words.data(), bytes, size);
  if (!pluginSpirv().emplace(name, std::move(words)).second)
    throw std::runtime_error("SPIR-V '" + name + "' registered twice");
}

bool spirvExists(const std::string& name) {
  std::error_code ec;
  return pluginSpirv().count(name) || std::filesystem::is_regular_file(shaderDir() + "/" + name, ec);
}

vk::Unique<VkShaderModule> loadShaderModule(Context& ctx, const std::string& name) {
  std::vector<uint32_t> code;
  auto plugin = pluginSpirv().find(name);
  if (plugin != pluginSpirv().end()) {
    code = plugin->second;
  } else {
    std::string path = shaderDir() + "/" + name;
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) throw std::runtime_error("cannot open shader " + path + " (build the project, or set LODBENCH_SHADER_DIR)");
    code.resize(size_t(f.tellg()) / 4);
    f.seekg(0);
    f.read(reinterpret_cast<char*>(code.data()), std::streamsize(code.size() * 4));
  }
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = code.size() * 4;
  ci.pCode = code.data();
  VkShaderModule m;
  VK_CHECK(vkCreateShaderModule(ctx.device, &ci, nullptr, &m));
  return vk::Unique(ctx.device, m);
}

}  // namespace lb
