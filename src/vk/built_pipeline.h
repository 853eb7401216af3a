// A pipeline of any kind with its layout: what a shader program is built into. Hot reload builds one off the
// render thread and hands it to its pass at a frame boundary (render/pass.h).
#pragma once
#include <memory>
#include <vulkan/vulkan.h>

#include "vk/graphics_pipeline.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

namespace wb::vk {

struct BuiltPipeline {
  std::unique_ptr<PipelineLayout> layout;
  // Exactly one of these holds the pipeline.
  std::unique_ptr<RayTracingPipeline> rayTracing;
  std::unique_ptr<GraphicsPipeline> graphics;
  std::unique_ptr<ComputePipeline> compute;

  VkPipeline handle() const {
    return rayTracing ? rayTracing->handle()
           : graphics ? graphics->handle()
           : compute  ? compute->handle()
                      : VK_NULL_HANDLE;
  }
  VkPipelineBindPoint bindPoint() const {
    return rayTracing ? VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR
           : graphics ? VK_PIPELINE_BIND_POINT_GRAPHICS
                      : VK_PIPELINE_BIND_POINT_COMPUTE;
  }
  // What linking a ray tracing pipeline from libraries took (all zero otherwise).
  RtLibraryStats libraryStats() const { return rayTracing ? rayTracing->libraryStats() : RtLibraryStats{}; }
};

}  // namespace wb::vk
