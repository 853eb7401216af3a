#include "vk/graphics_pipeline.h"

#include <chrono>

namespace wb::vk {

GraphicsPipeline::GraphicsPipeline(Context& ctx,
                                   const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages,
                                   const GraphicsPipelineDesc& desc, VkPipelineLayout layout,
                                   const std::vector<SpecializationConstant>& constants)
    : ctx_(ctx), desc_(desc) {
  auto t0 = std::chrono::steady_clock::now();
  const Specialization spec(constants);
  std::vector<ShaderModule> modules;  // only needed while the pipeline is created
  std::vector<VkPipelineShaderStageCreateInfo> stageInfos;
  for (const auto& s : stages) {
    if (s->stage != shader::Stage::Vertex && s->stage != shader::Stage::Fragment) {
      throw VulkanError(std::string("graphics pipeline: unexpected stage ") + shader::stageName(s->stage) +
                        " (" + s->key.path.string() + ")");
    }
    modules.emplace_back(ctx.device(), *s);
    stageInfos.push_back(modules.back().stageInfo(spec.info()));
  }
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cullMode;
  raster.frontFace = desc.frontFace;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depthFormat != VK_FORMAT_UNDEFINED && desc.depthTest;
  depth.depthWriteEnable = desc.depthFormat != VK_FORMAT_UNDEFINED && desc.depthWrite;
  depth.depthCompareOp = desc.depthCompare;
  std::vector<VkPipelineColorBlendAttachmentState> blends(desc.colorFormats.size());
  for (auto& b : blends) {
    b = {};
    b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                       VK_COLOR_COMPONENT_A_BIT;
  }
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = static_cast<uint32_t>(blends.size());
  blend.pAttachments = blends.data();
  const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamicStates;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<uint32_t>(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();
  rendering.depthAttachmentFormat = desc.depthFormat;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  if (desc.renderPass) {
    ci.renderPass = desc.renderPass;
  } else {
    ci.pNext = &rendering;
  }
  ci.stageCount = static_cast<uint32_t>(stageInfos.size());
  ci.pStages = stageInfos.data();
  ci.pVertexInputState = &vertexInput;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &viewport;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &multisample;
  ci.pDepthStencilState = &depth;
  ci.pColorBlendState = &blend;
  ci.pDynamicState = &dynamic;
  ci.layout = layout;
  WB_VK(vkCreateGraphicsPipelines(ctx.device(), ctx.pipelineCache(), 1, &ci, nullptr, &pipeline_));
  createMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

GraphicsPipeline::~GraphicsPipeline() {
  if (pipeline_) vkDestroyPipeline(ctx_.device(), pipeline_, nullptr);
}

ComputePipeline::ComputePipeline(Context& ctx, const shader::CompiledShader& stage, VkPipelineLayout layout,
                                 const std::vector<SpecializationConstant>& constants)
    : ctx_(ctx) {
  if (stage.stage != shader::Stage::Compute) {
    throw VulkanError(std::string("compute pipeline: unexpected stage ") + shader::stageName(stage.stage) +
                      " (" + stage.key.path.string() + ")");
  }
  const Specialization spec(constants);
  const ShaderModule module(ctx.device(), stage);
  VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  ci.stage = module.stageInfo(spec.info());
  ci.layout = layout;
  WB_VK(vkCreateComputePipelines(ctx.device(), ctx.pipelineCache(), 1, &ci, nullptr, &pipeline_));
}

ComputePipeline::~ComputePipeline() {
  if (pipeline_) vkDestroyPipeline(ctx_.device(), pipeline_, nullptr);
}

void setViewportAndScissor(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
  VkViewport vp{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  VkRect2D sc{{0, 0}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &sc);
}

}  // namespace wb::vk
