#pragma once
// The one place that builds a terrain graphics pipeline, for the renderer and the probe alike,
// so the probe's floor is measured with the renderer's fixed-function state: a patch list (or, on
// the instanced path, a triangle list) of vec2 points, no culling, dynamic rendering into an optional colour and an
// optional depth attachment, one viewport the size of the frame.
#include <vulkan/vulkan.h>

#include <array>
#include <string>
#include <vector>

#include "vk/unique.h"

namespace lb {

struct Context;

struct ShaderStage {
  VkShaderStageFlagBits stage;
  std::string spirv;  // file name in the SPIR-V directory (vk/resources.h shaderDir)
  const VkSpecializationInfo* specialization = nullptr;
};

struct TessPipelineDesc {
  VkPipelineLayout layout = VK_NULL_HANDLE;
  std::vector<ShaderStage> stages;
  // PATCH_LIST for the tessellation path (controlPoints per patch), TRIANGLE_LIST for the instanced
  // one; unused where a mesh stage makes the triangles (no vertex input either).
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST;
  uint32_t controlPoints = 4;
  uint32_t width = 0, height = 0;  // viewport and scissor
  VkPolygonMode polygonMode = VK_POLYGON_MODE_FILL;
  bool rasterizerDiscard = false;
  bool depthBias = false;
  float depthBiasConstant = 0, depthBiasSlope = 0;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
  VkFormat colorFormat = VK_FORMAT_UNDEFINED;  // UNDEFINED: no colour attachment
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;  // UNDEFINED: no depth attachment
  VkPipelineColorBlendAttachmentState blend{VK_FALSE,
                                            VK_BLEND_FACTOR_ZERO,
                                            VK_BLEND_FACTOR_ZERO,
                                            VK_BLEND_OP_ADD,
                                            VK_BLEND_FACTOR_ZERO,
                                            VK_BLEND_FACTOR_ZERO,
                                            VK_BLEND_OP_ADD,
                                            0xf};
  std::array<float, 4> blendConstants{};
  // The page arrays the terrain's heights fill (render/height_pages.h), given to every stage as
  // specialization constant LB_SPEC_HEIGHT_ARRAYS; 0: not given (the shaders read as though all
  // arrays were filled, which is right for any terrain, only slower on some drivers).
  uint32_t heightArrays = 0;
  // The same for the normal map's page arrays (render/normal_pages.h): LB_SPEC_NORMAL_ARRAYS.
  uint32_t normalArrays = 0;
};

// Loads the stages' modules, builds the pipeline and releases the modules (also when it throws).
vk::Unique<VkPipeline> createTessPipeline(Context& ctx, const TessPipelineDesc& desc);
// A compute pipeline of shaders/<stem>.comp on `layout` (one-off preprocessing passes and the
// GPU-indirect path's LOD passes alike).
// `spec`: the value of specialization constant 0 (uint), when the shader declares one.
vk::Unique<VkPipeline> createComputePipeline(Context& ctx, VkPipelineLayout layout, const std::string& stem,
                                             const uint32_t* spec = nullptr);

}  // namespace lb
