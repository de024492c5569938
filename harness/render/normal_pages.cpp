#include "render/normal_pages.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

#include "error.h"
#include "render/page_arrays.h"
#include "shaders/shared.h"
#include "terrain/normal_map.h"
#include "vk/context.h"
#include "vk/device_limits.h"

namespace lb {
namespace {

NormalPageLayout layoutFor(int width, int height, int cells, uint32_t maxImageArrayLayers, uint64_t maxAllocationBytes,
                           uint32_t maxLayers) {
  return normalPageLayout(width, height, cells, [&](uint64_t pageBytes) {
    uint32_t perArray = pageLayersPerArray(maxImageArrayLayers, maxAllocationBytes, pageBytes);
    if (maxLayers > 0) perArray = std::min(perArray, maxLayers);
    return uint64_t(perArray) * LB_NORMAL_ARRAYS;
  });
}

}  // namespace

NormalPagesFit normalPagesFit(int width, int height, uint32_t maxImageArrayLayers, uint64_t maxAllocationBytes) {
  const NormalPageLayout l = layoutFor(width, height, 0, maxImageArrayLayers, maxAllocationBytes, 0);
  NormalPagesFit f;
  f.cells = l.cells;
  f.perArray = pageLayersPerArray(maxImageArrayLayers, maxAllocationBytes, l.pageBytes());
  f.bytes = l.pageBytes() * uint64_t(l.pageCount());
  f.arrays = (uint64_t(l.pageCount()) + f.perArray - 1) / f.perArray;
  return f;
}

bool normalMapFitsOneImage(int width, int height, uint32_t maxImageDimension2D, uint64_t maxAllocationBytes) {
  // Level 0's bytes and the chain's third, as the driver lays out a mip-mapped image at most.
  const uint64_t level0 = uint64_t(width) * uint64_t(height) * 4;
  return uint32_t(std::max(width, height)) <= maxImageDimension2D &&
         level0 + level0 / 3 + (1u << 20) <= maxAllocationBytes;
}

// A 1 x 1 image or one-layer array of the map's format, for the bindings the shader does not read.
static Image standIn(Context& ctx, bool array, MemoryTag tag) {
  const uint16_t texel[2] = {0, 0};
  Image img = array ? createImageArray(ctx, 1, 1, 1, VK_FORMAT_R16G16_SFLOAT,
                                       VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, tag)
                    : createImage(ctx, 1, 1, VK_FORMAT_R16G16_SFLOAT,
                                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                  VK_IMAGE_ASPECT_COLOR_BIT, tag, 1);
  uploadImageLevels(ctx, img, {{texel, sizeof texel}});
  return img;
}

// The levels from `first` on as one image with its mips, trilinear by the sampler.
static void uploadLevels(Context& ctx, const NormalMap& nm, int first, MemoryTag tag, NormalPages& out) {
  out.image = createImage(ctx, uint32_t(nm.levelWidth(first)), uint32_t(nm.levelHeight(first)), VK_FORMAT_R16G16_SFLOAT,
                          VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT, tag,
                          uint32_t(nm.levels() - first));
  std::vector<ImageLevelData> levels;
  for (int k = first; k < nm.levels(); ++k)
    levels.push_back({nm.levelTexels(k).data(), nm.levelTexels(k).size() * sizeof(uint16_t)});
  uploadImageLevels(ctx, out.image, levels);
  // Trilinear over every level: terrain.frag chooses the level (textureLod), never the derivatives.
  out.linear = createSampler(ctx, VK_FILTER_LINEAR, float(nm.levels() - first - 1));
}

NormalPages createNormalPages(Context& ctx, const NormalMap& nm, MemoryTag tag, int cells, uint32_t maxLayers,
                              NormalPageDefect defect, int coarseFrom) {
  NormalPages out;
  const DeviceLimits limits = deviceLimits(ctx.physicalDevice);
  out.paged = cells > 0 || !normalMapFitsOneImage(nm.width, nm.height, ctx.props.limits.maxImageDimension2D,
                                                  limits.maxAllocationBytes);
  if (!out.paged) {
    uploadLevels(ctx, nm, 0, tag, out);
    out.arrays.push_back(standIn(ctx, true, tag));
    const int32_t table[8] = {1, 1, 1, 0, 1, 1, 0, 1};
    out.table = createBufferWithData(ctx, table, sizeof table, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, tag);
    return out;
  }
  out.coarseFrom = coarseFrom;
  if (coarseFrom == 0)
    for (out.coarseFrom = 1; out.coarseFrom < nm.levels(); ++out.coarseFrom)
      if (normalMapFitsOneImage(nm.levelWidth(out.coarseFrom), nm.levelHeight(out.coarseFrom),
                                ctx.props.limits.maxImageDimension2D, limits.maxAllocationBytes))
        break;
  out.coarseFrom = std::clamp(out.coarseFrom, 1, nm.levels());
  if (out.coarseFrom < nm.levels()) {
    uploadLevels(ctx, nm, out.coarseFrom, tag, out);
  } else {
    out.image = standIn(ctx, false, tag);
    out.linear = createSampler(ctx, VK_FILTER_LINEAR, 0.0f);
  }
  const uint32_t maxArrayLayers = ctx.props.limits.maxImageArrayLayers;
  const NormalPageLayout l =
      layoutFor(nm.width, nm.height, cells, maxArrayLayers, limits.maxAllocationBytes, maxLayers);
  out.layout = l;
  out.perArray = pageLayersPerArray(maxArrayLayers, limits.maxAllocationBytes, l.pageBytes());
  if (maxLayers > 0) out.perArray = std::min(out.perArray, maxLayers);
  const int pages = l.pageCount();
  const uint64_t arrays = (uint64_t(pages) + out.perArray - 1) / out.perArray;
  if (arrays > LB_NORMAL_ARRAYS)
    throw FeatureMissing("the normal map of " + std::to_string(nm.width) + " x " + std::to_string(nm.height) +
                         " samples in " + std::to_string(pages) + " pages of " + std::to_string(l.cells) +
                         " texels needs " + std::to_string(arrays) + " page arrays of " + std::to_string(out.perArray) +
                         " layers; the shaders bind " + std::to_string(LB_NORMAL_ARRAYS));
  const uint32_t stored = uint32_t(l.cells + 1);
  out.arrays = uploadPageArrays(
      ctx, stored, stored, VK_FORMAT_R16G16_SFLOAT, 4, pages, out.perArray, tag, [&](int p, void* dst) {
        auto* texels = static_cast<uint16_t*>(dst);
        copyNormalPage(nm, l, p, texels);
        if (defect != NormalPageDefect::OriginOffByOne) return;
        int k = int(l.levels.size()) - 1;
        while (k > 0 && l.levels[size_t(k)].first > p) --k;
        if ((p - l.levels[size_t(k)].first) % l.levels[size_t(k)].pagesX == 0) return;
        for (uint32_t z = 0; z < stored; ++z)  // each row one texel further along x
          std::memmove(texels + z * stored * 2, texels + z * stored * 2 + 2, (stored - 1) * 4);
      });
  std::vector<int32_t> table(4 + 4 * l.levels.size());
  table[0] = int32_t(l.levels.size()), table[1] = l.cells, table[2] = int32_t(out.perArray);
  table[3] = out.coarseFrom;
  for (size_t k = 0; k < l.levels.size(); ++k) {
    const NormalPageLevel& v = l.levels[k];
    std::memcpy(&table[4 + 4 * k], std::array<int32_t, 4>{v.width, v.height, v.first, v.pagesX}.data(), 16);
  }
  out.table = createBufferWithData(ctx, table.data(), VkDeviceSize(table.size()) * sizeof(int32_t),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, tag);
  return out;
}

void writeNormalDescriptors(Context& ctx, VkDescriptorSet set, const NormalPages& pages, VkSampler sampler) {
  writePageDescriptors(ctx, set, LB_BINDING_NORMAL_PAGES, LB_NORMAL_ARRAYS, pages.arrays, LB_BINDING_NORMAL_TABLE,
                       pages.table, sampler);
  VkDescriptorImageInfo image{pages.linear.get(), pages.image.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.dstBinding = LB_BINDING_NORMAL;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = &image;
  vkUpdateDescriptorSets(ctx.device, 1, &w, 0, nullptr);
}

std::vector<DescriptorBinding> normalBindings(VkShaderStageFlags stages) {
  return {{LB_BINDING_NORMAL, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, stages},
          {LB_BINDING_NORMAL_PAGES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, stages, LB_NORMAL_ARRAYS},
          {LB_BINDING_NORMAL_TABLE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, stages}};
}

}  // namespace lb
