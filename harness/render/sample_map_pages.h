#pragma once
// A scheme's per-sample map on the device (render/scheme.h SampleMap): R32F pages cut as the heights
// are (terrain/page_layout.h) in arrays of the same layer counts, so shaders/sample_map.glsl finds a
// sample through the heights' own page table. A map past one image is then no special case, and the
// map is computed page by page into the upload's bounded staging: it never exists whole on the host.
#include <vector>

#include "render/height_pages.h"
#include "vk/resources.h"

namespace lb {

struct Context;
struct SampleMap;

std::vector<Image> createSampleMapPages(Context& ctx, const HeightPages& heights, const SampleMap& map, MemoryTag tag);

// Writes LB_BINDING_SAMPLE_MAP of `set`: the map's arrays, or the heights' arrays where the scheme has
// no map (every binding of the renderer's set holds a valid image).
void writeSampleMapDescriptors(Context& ctx, VkDescriptorSet set, const std::vector<Image>& arrays,
                               const HeightPages& heights, VkSampler sampler);
DescriptorBinding sampleMapBinding(VkShaderStageFlags stages);

// The map read back from the device, row-major over the terrain's samples (tests).
std::vector<float> readSampleMapPages(Context& ctx, const HeightPages& heights, const std::vector<Image>& arrays);

}  // namespace lb
