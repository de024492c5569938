#pragma once
// CPU port of shaders/terrain.frag's LB_MODE_SHADED colour, so the ray-cast ground truth
// (raycast.h) is shaded exactly as the renderer shades: per-pixel normal from the terrain's normal
// map, filtered at the level of the pixel's footprint (shaders/footprint.h) (terrain/normal_map.h, the texels the
// renderer uploads), one directional light (Renderer::fillUniforms), slope-blended base colour, clear colour pure
// magenta.
#include <array>
#include <cstdint>
#include <glm/glm.hpp>

namespace lb {

struct NormalMap;

constexpr std::array<uint8_t, 4> kClearRgba = {255, 0, 255, 255};
// The slope range over which grass blends into rock (terrain.frag's smoothstep edges).
constexpr float kSlopeBlendLow = 0.15f, kSlopeBlendHigh = 0.35f;
// The light of Renderer::fillUniforms, normalised in float: shadeTerrain's and the GPU ray cast's.
glm::vec3 shadeLight();

// RGBA8 (UNORM, round to nearest) of the terrain surface at world (x, z), in float arithmetic as
// the shader does it. `normals` is computeNormalMap() of the heightfield, extent its Heightfield::extent;
// level the normal map's mip level there (shadingLevel, shaders/footprint.h).
std::array<uint8_t, 4> shadeTerrain(const NormalMap& normals, float extent, float x, float z, float level);

}  // namespace lb
