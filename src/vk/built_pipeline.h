// A pipeline of any kind with its layout: what a shader program is built into. Hot reload builds one off the
// render thread and hands it to its owner at a frame boundary (render/hot_reload.h).
#pragma once
#include <memory>
#include <utility>
#include <vulkan/vulkan.h>

#include "vk/graphics_pipeline.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

namespace wb::vk {

// A VkPipeline made directly (compute, or graphics for a render pass), destroyed with its owner.
class OwnedPipeline {
 public:
  OwnedPipeline() = default;
  OwnedPipeline(VkDevice device, VkPipeline pipeline) : device_(device), pipeline_(pipeline) {}
  ~OwnedPipeline() {
    if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
  }
  OwnedPipeline(OwnedPipeline&& o) noexcept
      : device_(o.device_), pipeline_(std::exchange(o.pipeline_, VK_NULL_HANDLE)) {}
  OwnedPipeline& operator=(OwnedPipeline&& o) noexcept {
    std::swap(device_, o.device_);
    std::swap(pipeline_, o.pipeline_);
    return *this;
  }
  VkPipeline handle() const { return pipeline_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

struct BuiltPipeline {
  std::unique_ptr<PipelineLayout> layout;
  // Exactly one of these holds the pipeline.
  std::unique_ptr<RayTracingPipeline> rayTracing;
  std::unique_ptr<GraphicsPipeline> graphics;  // dynamic rendering
  OwnedPipeline other;                         // compute, or graphics for a render pass

  VkPipeline handle() const {
    return rayTracing ? rayTracing->handle() : graphics ? graphics->handle() : other.handle();
  }
  // What linking a ray tracing pipeline from libraries took (all zero otherwise).
  RtLibraryStats libraryStats() const { return rayTracing ? rayTracing->libraryStats() : RtLibraryStats{}; }
};

}  // namespace wb::vk
