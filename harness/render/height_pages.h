#pragma once
// The heightfield on the device (docs/tiled-heightfield.md): its pages (terrain/page_layout.h) as
// layers of R32F 2D array images and the page table that shaders/heights.glsl reads them through.
// Every pass that reads heights binds these: the renderer's set and a scheme's compute pass alike.
#include <vector>

#include "terrain/page_layout.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct Heightfield;

struct HeightPages {
  PageLayout layout;
  std::vector<Image> arrays;  // up to LB_HEIGHT_ARRAYS, each as many layers as the device allows
  Buffer table;               // HeightTableHeader, then one entry per page (shaders/shared.h)
};

// Cuts hf into pageLayout(hf) and uploads every page, charged to `tag` (the heights). Pages fill
// arrays of at most min(maxImageArrayLayers, 2048) layers and most of maxMemoryAllocationSize;
// throws FeatureMissing when more than LB_HEIGHT_ARRAYS arrays would be needed. `maxLayers` > 0
// caps the layers an array holds (testing only: RenderSettings::testPageLayers).
HeightPages createHeightPages(Context& ctx, const Heightfield& hf, MemoryTag tag, PageDefect defect = PageDefect::None,
                              uint32_t maxLayers = 0);

// Writes LB_BINDING_HEIGHT (every element of the descriptor array; those the terrain does not need
// repeat the first array) and LB_BINDING_HEIGHT_TABLE of `set`.
void writeHeightDescriptors(Context& ctx, VkDescriptorSet set, const HeightPages& pages, VkSampler sampler);
// The two bindings as createBindings takes them.
std::vector<DescriptorBinding> heightBindings(VkShaderStageFlags stages);

}  // namespace lb
