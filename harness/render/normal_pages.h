#pragma once
// The normal map on the device (docs/tiled-heightfield.md), built once per terrain by the renderer.
// A map that fits one image is one RG16F image with every level, filtered by the sampler
// (trilinear at the shader's level): the fastest read, one instruction. A map past one image (the
// device's maxImageDimension2D or largest allocation) is every level in pages
// (terrain/normal_page_layout.h) as layers of RG16F 2D array images behind a level table,
// filtered in the shader (shaders/normals.glsl), and its coarse levels, from the first that fits
// one image, also as one image read by the sampler: a distant pixel (the most of a frame over a
// large terrain) reads as fast as from an unpaged map, and only pixels finer than that level take
// the shader's filter. The shader takes one or the other by a specialization constant; bindings it
// does not read hold 1 x 1 stand-ins.
#include <vector>

#include "terrain/normal_page_layout.h"
#include "vk/resources.h"

namespace lb {

struct Context;

struct NormalPages {
  bool paged = false;
  Image image;                   // !paged: the map, every level; paged: levels coarseFrom.. or a stand-in
  int coarseFrom = 0;            // paged: the map's level that is image's level 0 (levels(): none)
  vk::Unique<VkSampler> linear;  // trilinear over the image's levels
  NormalPageLayout layout;
  uint32_t perArray = 1;      // layers an array holds
  std::vector<Image> arrays;  // up to LB_NORMAL_ARRAYS
  Buffer table;               // header, then one ivec4 per level (shaders/normals.glsl)
};

// Testing only: pages after the first of a row start one texel too far along x, a defect the
// paging test (tests/test_normal_pages.cpp) must see.
enum class NormalPageDefect { None, OriginOffByOne };

// Pages when the map does not fit one image or `cells` > 0 (testing: pages of that size);
// `maxLayers` > 0 caps an array's layers (testing). With pages, `coarseFrom` > 0 makes the levels
// from it on the one image (testing; a value past the map's levels: none); 0 takes the first level
// from 1 on whose chain fits one image. Throws FeatureMissing when the pages need more than
// LB_NORMAL_ARRAYS arrays.
NormalPages createNormalPages(Context& ctx, const NormalMap& nm, MemoryTag tag, int cells = 0, uint32_t maxLayers = 0,
                              NormalPageDefect defect = NormalPageDefect::None, int coarseFrom = 0);
// The pages' device bytes and array count for a width x height terrain on a device with these
// limits (render/terrain_fit.cpp checks them before any work); arrays > LB_NORMAL_ARRAYS: too large.
struct NormalPagesFit {
  uint64_t bytes = 0;
  uint64_t arrays = 0;
  uint32_t perArray = 1;
  int cells = 1;
};
NormalPagesFit normalPagesFit(int width, int height, uint32_t maxImageArrayLayers, uint64_t maxAllocationBytes);

// Whether a width x height map fits one image of this device (its side and its bytes, every level).
bool normalMapFitsOneImage(int width, int height, uint32_t maxImageDimension2D, uint64_t maxAllocationBytes);

// Writes LB_BINDING_NORMAL, LB_BINDING_NORMAL_PAGES (every element; those the map does not fill
// repeat the first array) and LB_BINDING_NORMAL_TABLE of `set`.
void writeNormalDescriptors(Context& ctx, VkDescriptorSet set, const NormalPages& pages, VkSampler sampler);
// The three bindings as createBindings takes them.
std::vector<DescriptorBinding> normalBindings(VkShaderStageFlags stages);

}  // namespace lb
