// A ray tracing pipeline from compiled stages and shader groups, with its shader binding table.
#pragma once
#include <memory>
#include <vector>
#include <vulkan/vulkan.h>

#include "shader/types.h"
#include "vk/sbt.h"

namespace wb::vk {

// A group refers to stages by their index in the stage list; -1 = unused.
struct RtShaderGroup {
  int general = -1;  // raygen, miss or callable
  int closestHit = -1;
  int anyHit = -1;
  int intersection = -1;
};

struct SpecializationConstant {
  uint32_t id = 0;
  uint32_t value = 0;
};

class RayTracingPipeline {
 public:
  // Groups must come in SBT order: one raygen, then `missCount` miss groups, then the hit groups.
  RayTracingPipeline(Context& ctx, const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages,
                     const std::vector<RtShaderGroup>& groups, uint32_t missCount, VkPipelineLayout layout,
                     uint32_t maxRecursionDepth, const std::vector<SpecializationConstant>& constants = {});
  ~RayTracingPipeline();
  RayTracingPipeline(const RayTracingPipeline&) = delete;
  RayTracingPipeline& operator=(const RayTracingPipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  const ShaderBindingTable& sbt() const { return sbt_; }
  double createMs() const { return createMs_; }

 private:
  Context& ctx_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  ShaderBindingTable sbt_;
  double createMs_ = 0;
};

}  // namespace wb::vk
