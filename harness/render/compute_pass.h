#pragma once
// A scheme's one-off GPU preprocessing (docs/design.md, Schemes): a compute shader reads the heightfield
// and writes an RGBA32F image that the tessellation stages sample afterwards.
#include <string>
#include <vector>

#include "vk/resources.h"

namespace lb {

struct Context;
struct ComputePush;
struct HeightPages;

// Runs shaders/<stem>.comp once as output.width x output.height workgroups (one per texel) with
// the heightfield's pages at LB_BINDING_HEIGHT and LB_BINDING_HEIGHT_TABLE (shaders/heights.glsl) and
// `output` as a storage image at LB_BINDING_SCHEME_IMAGE.
// `output` needs STORAGE and SAMPLED usage; it is left in SHADER_READ_ONLY_OPTIMAL. Waits for the GPU.
void runComputePass(Context& ctx, const std::string& stem, VkSampler sampler, const HeightPages& heights,
                    const Image& output, const ComputePush& push);

// Copies an RGBA32F image in SHADER_READ_ONLY_OPTIMAL (with TRANSFER_SRC usage) to the host,
// width * height * 4 floats, and leaves it in SHADER_READ_ONLY_OPTIMAL. Set-up and tests only.
// Every layer, one after the other (an array's pages: render/sample_map_pages.h).
std::vector<float> readImageRgba32f(Context& ctx, const Image& image, int channels = 4);  // 1: an R32_SFLOAT image

}  // namespace lb
