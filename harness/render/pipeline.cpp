#include "render/pipeline.h"

#include <cstring>

#include "shaders/shared.h"
#include "vk/context.h"
#include "vk/resources.h"
#include "vk/vk_check.h"

namespace lb {

vk::Unique<VkPipeline> createTessPipeline(Context& ctx, const TessPipelineDesc& desc) {
  std::vector<vk::Unique<VkShaderModule>> modules;
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  // Each stage's own constants, then the page arrays' counts (a constant a stage does not declare is
  // ignored): sized up front, so the pointers into them hold until the pipeline is made.
  std::vector<std::vector<VkSpecializationMapEntry>> entries(desc.stages.size());
  std::vector<std::vector<uint8_t>> data(desc.stages.size());
  std::vector<VkSpecializationInfo> specs(desc.stages.size());
  for (size_t i = 0; i < desc.stages.size(); ++i) {
    const ShaderStage& s = desc.stages[i];
    modules.push_back(loadShaderModule(ctx, s.spirv));
    VkPipelineShaderStageCreateInfo st{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    st.stage = s.stage;
    st.module = modules.back();
    st.pName = "main";
    st.pSpecializationInfo = s.specialization;
    if (desc.heightArrays > 0 || desc.normalArrays > 0) {
      const VkSpecializationInfo* own = s.specialization;
      if (own) {
        entries[i].assign(own->pMapEntries, own->pMapEntries + own->mapEntryCount);
        data[i].assign(static_cast<const uint8_t*>(own->pData),
                       static_cast<const uint8_t*>(own->pData) + own->dataSize);
      }
      auto add = [&](uint32_t id, uint32_t value) {
        if (value == 0) return;
        data[i].resize((data[i].size() + 3) / 4 * 4);
        entries[i].push_back({id, uint32_t(data[i].size()), sizeof(int32_t)});
        const int32_t v = int32_t(value);
        data[i].resize(data[i].size() + sizeof v);
        std::memcpy(data[i].data() + data[i].size() - sizeof v, &v, sizeof v);
      };
      add(LB_SPEC_HEIGHT_ARRAYS, desc.heightArrays);
      add(LB_SPEC_NORMAL_ARRAYS, desc.normalArrays);
      specs[i] = {uint32_t(entries[i].size()), entries[i].data(), data[i].size(), data[i].data()};
      st.pSpecializationInfo = &specs[i];
    }
    stages.push_back(st);
  }
  // A mesh pipeline reads no vertices: no vertex input or input assembly state.
  bool mesh = false;
  for (const ShaderStage& s : desc.stages) mesh = mesh || s.stage == VK_SHADER_STAGE_MESH_BIT_EXT;
  VkVertexInputBindingDescription vb{0, sizeof(float) * 2, VK_VERTEX_INPUT_RATE_VERTEX};
  VkVertexInputAttributeDescription va{0, 0, VK_FORMAT_R32G32_SFLOAT, 0};
  VkPipelineVertexInputStateCreateInfo vi{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vi.vertexBindingDescriptionCount = 1;
  vi.pVertexBindingDescriptions = &vb;
  vi.vertexAttributeDescriptionCount = 1;
  vi.pVertexAttributeDescriptions = &va;
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = desc.topology;
  VkPipelineTessellationStateCreateInfo ts{VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO};
  ts.patchControlPoints = desc.controlPoints;
  VkViewport viewport{0, 0, float(desc.width), float(desc.height), 0, 1};
  VkRect2D scissor{{0, 0}, {desc.width, desc.height}};
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = 1;
  vp.pViewports = &viewport;
  vp.scissorCount = 1;
  vp.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = desc.polygonMode;
  rs.cullMode = VK_CULL_MODE_NONE;  // back faces are counted by the histogram pass, not hidden
  rs.lineWidth = 1.0f;
  rs.depthBiasEnable = desc.depthBias;
  rs.depthBiasConstantFactor = desc.depthBiasConstant;
  rs.depthBiasSlopeFactor = desc.depthBiasSlope;
  rs.rasterizerDiscardEnable = desc.rasterizerDiscard;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  ds.depthTestEnable = VK_TRUE;
  ds.depthWriteEnable = VK_TRUE;
  ds.depthCompareOp = desc.depthCompare;
  const bool colour = desc.colorFormat != VK_FORMAT_UNDEFINED;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  for (int i = 0; i < 4; ++i) cb.blendConstants[i] = desc.blendConstants[size_t(i)];
  cb.attachmentCount = colour ? 1 : 0;
  cb.pAttachments = colour ? &desc.blend : nullptr;
  VkPipelineRenderingCreateInfo ri{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  ri.colorAttachmentCount = colour ? 1 : 0;
  ri.pColorAttachmentFormats = colour ? &desc.colorFormat : nullptr;
  ri.depthAttachmentFormat = desc.depthFormat;
  VkGraphicsPipelineCreateInfo gi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &ri};
  gi.stageCount = uint32_t(stages.size());
  gi.pStages = stages.data();
  gi.pVertexInputState = mesh ? nullptr : &vi;
  gi.pInputAssemblyState = mesh ? nullptr : &ia;
  gi.pTessellationState = !mesh && desc.topology == VK_PRIMITIVE_TOPOLOGY_PATCH_LIST ? &ts : nullptr;
  gi.pViewportState = &vp;
  gi.pRasterizationState = &rs;
  gi.pMultisampleState = &ms;
  gi.pDepthStencilState = &ds;
  gi.pColorBlendState = &cb;
  gi.layout = desc.layout;
  VkPipeline pipeline;
  VK_CHECK(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &gi, nullptr, &pipeline));
  return vk::Unique(ctx.device, pipeline);
}

vk::Unique<VkPipeline> createComputePipeline(Context& ctx, VkPipelineLayout layout, const std::string& stem,
                                             const uint32_t* spec) {
  vk::Unique<VkShaderModule> module = loadShaderModule(ctx, stem + ".comp.spv");
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  ci.stage.module = module;
  ci.stage.pName = "main";
  VkSpecializationMapEntry entry{0, 0, sizeof(uint32_t)};
  VkSpecializationInfo specInfo{1, &entry, sizeof(uint32_t), spec};
  if (spec) ci.stage.pSpecializationInfo = &specInfo;
  ci.layout = layout;
  VkPipeline raw;
  VK_CHECK(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &ci, nullptr, &raw));
  return vk::Unique(ctx.device, raw);
}

}  // namespace lb
