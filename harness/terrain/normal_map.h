#pragma once
// Per-terrain normal map: computed once on the CPU at terrain load, uploaded by the renderer in
// pages (render/normal_pages.h) and filtered per pixel by shaders/normal_sample.glsl, which the GPU
// ray cast shares and sampleNormalMap below repeats on the CPU: the same texels and the same
// arithmetic, so the reference shades as the renderer does.
//
// Format: VK_FORMAT_R16G16_SFLOAT holding, per heightfield sample, the x and z components of the
// unnormalised normal (gx, 1, gz) = ((h[i-1] - h[i+1]) / 2dx, 1, (h[j-1] - h[j+1]) / 2dz), the
// central differences one texel apart that terrainNormal() (common.glsl) took per pixel before.
// Why this and not a unit normal in RGBA8_SNORM or RG16_SNORM with a reconstructed y:
//  - The old per-pixel gradient at any point is exactly the bilinear interpolation of these texel
//    gradients (the heightfield is bilinear and the differences are one texel apart, clamping
//    included), so filtering gradients and normalising after the fetch reproduces the old normal
//    up to rounding; filtering unit normals would not (interpolated unit vectors differ).
//  - float16 keeps 11 significant bits at any slope: steep DEM cliffs and near-flat valleys alike
//    (8-bit SNORM normals step by 1/127, about one RGBA8 output level of diffuse light).
//  - 4 bytes per texel, as RGBA8; linear filtering of R16G16_SFLOAT is mandatory in Vulkan.
// Slopes beyond the float16 range (|g| > 65504) are clamped: their normal is horizontal to 2e-5.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "uninit_vector.h"

namespace lb {

struct Heightfield;

// Mip levels 1, 2, ... (shaders/footprint.h chooses which one shades a pixel): level k has
// max(1, size >> k) texels a side (Vulkan's chain), each the mean of the gradients of the 2 x 2
// texels of level k - 1 it covers, and of the last row or column too where that level's size is odd
// (nothing is dropped): the mean gradient over the area, which is the gradient of the mean surface.
struct NormalMapLevel {
  int width = 0, height = 0;
  UninitVector<uint16_t> texels;
};

struct NormalMap {
  int width = 0, height = 0;            // the heightfield's sample counts
  UninitVector<uint16_t> texels;        // RG16F bit patterns (gx, gz), row-major, row = z: level 0
  std::vector<NormalMapLevel> coarser;  // levels 1 .. normalMapLevels(width, height) - 1
  int levels() const { return 1 + int(coarser.size()); }
  int levelWidth(int k) const { return k == 0 ? width : coarser[size_t(k - 1)].width; }
  int levelHeight(int k) const { return k == 0 ? height : coarser[size_t(k - 1)].height; }
  const UninitVector<uint16_t>& levelTexels(int k) const { return k == 0 ? texels : coarser[size_t(k - 1)].texels; }
};

// lanes: eight texels at a time where the processor converts to half (F16C); false: one at a
// time. The same bits either way (tests/test_normal_map.cpp).
NormalMap computeNormalMap(const Heightfield& hf, bool lanes = true);
bool normalMapLanes();  // whether this processor takes the lanes (AVX and F16C)

// Unit normal at terrain-local (x, z): bilinear filtering of the texels at texel coordinate
// t = clamp(p / extent, 0, 1) * (size - 1) (the centre of texel i is i), then normalize(gx, 1, gz),
// in float as shaders/normal_sample.glsl does it (the GPU may round a step differently).
//
// level > 0 (shadingLevel, shaders/footprint.h): trilinear: levels floor(level) and the next mixed
// by the fraction; at level k > 0 the texel coordinate is (t + 0.5) size_k / size - 0.5, both
// texels of an axis clamped to the edge.
glm::vec3 sampleNormalMap(const NormalMap& nm, float extent, float x, float z, float level = 0.0f);

uint16_t floatToHalf(float f);  // round to nearest even, clamped to the finite range
float halfToFloat(uint16_t h);

}  // namespace lb
