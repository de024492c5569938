#pragma once
// How long one draw may be on the tessellation path, for the renderer's split draws, the probe and
// the schemes that split their own (cbt-ts).
#include <cstdint>

namespace lb {

enum class Partitioning;

// Largest vertex count a single draw may produce (Mesa 22.3 lavapipe: 16-bit tessellator indices).
constexpr uint32_t kMaxVerticesPerDraw = 65535;
// Largest index count of a single draw: Mesa 22.3 lavapipe runs longer draws in 1024-index
// segments and restarts gl_PrimitiveID in each (measured), which breaks patchIndex().
constexpr uint32_t kMaxIndicesPerDraw = 1024;
// Upper bound of vertices one patch can generate at tessellation level `level`.
uint32_t maxVerticesPerPatch(float level, Partitioning partitioning);

}  // namespace lb
