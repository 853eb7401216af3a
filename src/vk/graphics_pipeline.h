// Graphics and compute pipelines from compiled stages, built on a vk::PipelineLayout made from the reflected
// layout. A graphics pipeline renders with dynamic rendering (Vulkan 1.3: the attachment formats are part of
// the pipeline) or, given one, into subpass 0 of a render pass (the window's swapchain pass).
#pragma once
#include <memory>
#include <vector>
#include <vulkan/vulkan.h>

#include "shader/types.h"
#include "vk/context.h"
#include "vk/rt_pipeline.h"

namespace wb::vk {

struct GraphicsPipelineDesc {
  std::vector<VkFormat> colorFormats;          // one per colour attachment, in location order
  VkFormat depthFormat = VK_FORMAT_UNDEFINED;  // UNDEFINED = no depth attachment
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cullMode = VK_CULL_MODE_NONE;
  VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depthTest = true;
  bool depthWrite = true;
  VkCompareOp depthCompare = VK_COMPARE_OP_LESS;
  VkRenderPass renderPass =
      VK_NULL_HANDLE;  // set: subpass 0 of this pass (colorFormats count its attachments)
};

class GraphicsPipeline {
 public:
  // `stages`: vertex (+ fragment) shaders. Viewport and scissor are dynamic state; no vertex input (vertices
  // are pulled in the vertex shader). Specialisation constants apply to every stage.
  GraphicsPipeline(Context& ctx, const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages,
                   const GraphicsPipelineDesc& desc, VkPipelineLayout layout,
                   const std::vector<SpecializationConstant>& constants = {});
  ~GraphicsPipeline();
  GraphicsPipeline(const GraphicsPipeline&) = delete;
  GraphicsPipeline& operator=(const GraphicsPipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  const GraphicsPipelineDesc& desc() const { return desc_; }
  double createMs() const { return createMs_; }

 private:
  Context& ctx_;
  GraphicsPipelineDesc desc_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  double createMs_ = 0;
};

// A compute pipeline from one compute stage.
class ComputePipeline {
 public:
  ComputePipeline(Context& ctx, const shader::CompiledShader& stage, VkPipelineLayout layout,
                  const std::vector<SpecializationConstant>& constants = {});
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;
  VkPipeline handle() const { return pipeline_; }

 private:
  Context& ctx_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Sets a full-size viewport (y down, depth 0..1) and scissor.
void setViewportAndScissor(VkCommandBuffer cmd, uint32_t width, uint32_t height);

}  // namespace wb::vk
