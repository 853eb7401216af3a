#include "vk/rt_pipeline.h"

#include <chrono>

namespace wb::vk {

RayTracingPipeline::RayTracingPipeline(
    Context& ctx, const std::vector<std::shared_ptr<const shader::CompiledShader>>& stages,
    const std::vector<RtShaderGroup>& groups, uint32_t missCount, VkPipelineLayout layout,
    uint32_t maxRecursionDepth, const std::vector<SpecializationConstant>& constants)
    : ctx_(ctx) {
  auto t0 = std::chrono::steady_clock::now();
  if (maxRecursionDepth > ctx.rayTracing().maxRecursionDepth) {
    throw VulkanError("ray recursion depth " + std::to_string(maxRecursionDepth) + " exceeds the device's " +
                      std::to_string(ctx.rayTracing().maxRecursionDepth));
  }
  std::vector<VkShaderModule> modules;
  std::vector<VkPipelineShaderStageCreateInfo> stageInfos;
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<uint32_t> values;
  for (const auto& c : constants) {
    entries.push_back({c.id, static_cast<uint32_t>(values.size() * sizeof(uint32_t)), sizeof(uint32_t)});
    values.push_back(c.value);
  }
  VkSpecializationInfo spec{static_cast<uint32_t>(entries.size()), entries.data(),
                            values.size() * sizeof(uint32_t), values.data()};
  auto cleanup = [&] {
    for (auto m : modules) vkDestroyShaderModule(ctx.device(), m, nullptr);
  };
  try {
    for (const auto& s : stages) {
      VkShaderModuleCreateInfo mci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
      mci.codeSize = s->spirv.size() * sizeof(uint32_t);
      mci.pCode = s->spirv.data();
      VkShaderModule m;
      WB_VK(vkCreateShaderModule(ctx.device(), &mci, nullptr, &m));
      modules.push_back(m);
      VkPipelineShaderStageCreateInfo si{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
      si.stage = shader::toVkStage(s->stage);
      si.module = m;
      si.pName = "main";
      si.pSpecializationInfo = constants.empty() ? nullptr : &spec;
      stageInfos.push_back(si);
    }
    std::vector<VkRayTracingShaderGroupCreateInfoKHR> groupInfos;
    for (const auto& g : groups) {
      VkRayTracingShaderGroupCreateInfoKHR gi{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
      gi.type = g.general >= 0        ? VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR
                : g.intersection >= 0 ? VK_RAY_TRACING_SHADER_GROUP_TYPE_PROCEDURAL_HIT_GROUP_KHR
                                      : VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
      auto idx = [](int i) { return i >= 0 ? static_cast<uint32_t>(i) : VK_SHADER_UNUSED_KHR; };
      gi.generalShader = idx(g.general);
      gi.closestHitShader = idx(g.closestHit);
      gi.anyHitShader = idx(g.anyHit);
      gi.intersectionShader = idx(g.intersection);
      groupInfos.push_back(gi);
    }
    VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
    ci.stageCount = static_cast<uint32_t>(stageInfos.size());
    ci.pStages = stageInfos.data();
    ci.groupCount = static_cast<uint32_t>(groupInfos.size());
    ci.pGroups = groupInfos.data();
    ci.maxPipelineRayRecursionDepth = maxRecursionDepth;
    ci.layout = layout;
    WB_VK(ctx.vkCreateRayTracingPipelinesKHR(ctx.device(), VK_NULL_HANDLE, ctx.pipelineCache(), 1, &ci,
                                             nullptr, &pipeline_));
    const uint32_t hitCount = static_cast<uint32_t>(groups.size()) - 1 - missCount;
    sbt_ = ShaderBindingTable(ctx, pipeline_, missCount, hitCount);
  } catch (...) {
    cleanup();
    if (pipeline_) vkDestroyPipeline(ctx.device(), pipeline_, nullptr);
    throw;
  }
  cleanup();
  createMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

RayTracingPipeline::~RayTracingPipeline() {
  if (pipeline_) vkDestroyPipeline(ctx_.device(), pipeline_, nullptr);
}

}  // namespace wb::vk
