#include "app/window/display_pass.h"

#include "common/paths.h"
#include "vk/shader_module.h"

namespace wb::app {

std::vector<shader::ShaderKey> DisplayPass::stageKeys() {
  const auto dir = shaderDir() / "display";
  return {{dir / "fullscreen.vert", std::nullopt, {}}, {dir / "display.frag", std::nullopt, {}}};
}

DisplayPass::DisplayPass(vk::Context& ctx, shader::ShaderLibrary& library, VkRenderPass renderPass)
    : ctx_(ctx), renderPass_(renderPass) {
  {
    vk::DescriptorSets recorder(ctx);
    writeDescriptors(recorder);
    provided_ = recorder.requested();
  }
  program_ = library.registerProgram("display", stageKeys());
  install(build(library.buildProgram(program_)));
}

DisplayPass::~DisplayPass() {
  ctx_.waitIdle();
  sets_.reset();
  current_.reset();
}

std::unique_ptr<vk::BuiltPipeline> DisplayPass::build(
    const shader::ShaderLibrary::ProgramBuild& build) const {
  vk::requireProvided(build, provided_, "the display pass");
  auto built = std::make_unique<vk::BuiltPipeline>();
  built->layout = std::make_unique<vk::PipelineLayout>(ctx_, build.layout);

  std::vector<vk::ShaderModule> modules;  // only needed while the pipeline is created
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  for (const auto& s : build.stages) {
    modules.emplace_back(ctx_.device(), *s);
    stages.push_back(modules.back().stageInfo());
  }
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                   VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &blendAttachment;
  const VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dyn{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dyn.dynamicStateCount = 2;
  dyn.pDynamicStates = dynamic;

  VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  ci.stageCount = static_cast<uint32_t>(stages.size());
  ci.pStages = stages.data();
  ci.pVertexInputState = &vertexInput;
  ci.pInputAssemblyState = &assembly;
  ci.pViewportState = &viewport;
  ci.pRasterizationState = &raster;
  ci.pMultisampleState = &ms;
  ci.pColorBlendState = &blend;
  ci.pDynamicState = &dyn;
  ci.layout = built->layout->handle();
  ci.renderPass = renderPass_;
  VkPipeline pipeline = VK_NULL_HANDLE;
  WB_VK(vkCreateGraphicsPipelines(ctx_.device(), ctx_.pipelineCache(), 1, &ci, nullptr, &pipeline));
  built->other = vk::OwnedPipeline(ctx_.device(), pipeline);
  return built;
}

void DisplayPass::install(std::unique_ptr<vk::BuiltPipeline> pipeline) {
  ctx_.waitIdle();
  sets_.reset();
  current_ = std::move(pipeline);
  sets_ = std::make_unique<vk::DescriptorSets>(ctx_, *current_->layout);
  if (sources_.accum) writeDescriptors(*sets_);
}

void DisplayPass::setSources(const DisplaySources& sources) {
  if (sources == sources_) return;
  sources_ = sources;
  if (sets_ && sources_.accum) writeDescriptors(*sets_);
}

void DisplayPass::writeDescriptors(vk::DescriptorSets& s) {
  s.writeStorageImage(0, WB_DISPLAY_BIND_ACCUM, sources_.accum);
  s.writeStorageImage(0, WB_DISPLAY_BIND_ALBEDO, sources_.albedo);
  s.writeStorageImage(0, WB_DISPLAY_BIND_NORMAL, sources_.normal);
  s.writeStorageImage(0, WB_DISPLAY_BIND_INFO, sources_.info);
  s.writeStorageImage(0, WB_DISPLAY_BIND_PREVIEW, sources_.preview);
  s.writeStorageImage(0, WB_DISPLAY_BIND_STATS, sources_.stats);
}

void DisplayPass::record(VkCommandBuffer cmd, const gpu::DisplayPush& push) const {
  VkViewport vp{push.viewRect.x, push.viewRect.y, push.viewRect.z, push.viewRect.w, 0.0f, 1.0f};
  VkRect2D scissor{{int32_t(push.viewRect.x), int32_t(push.viewRect.y)},
                   {uint32_t(push.viewRect.z), uint32_t(push.viewRect.w)}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, current_->handle());
  const auto& sets = sets_->sets();
  if (!sets.empty()) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, current_->layout->handle(), 0,
                            static_cast<uint32_t>(sets.size()), sets.data(), 0, nullptr);
  }
  for (const auto& range : current_->layout->desc().pushConstants) {
    vkCmdPushConstants(cmd, current_->layout->handle(), range.stageFlags, range.offset, range.size,
                       reinterpret_cast<const char*>(&push) + range.offset);
  }
  vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace wb::app
