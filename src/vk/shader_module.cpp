#include "vk/shader_module.h"

#include "vk/check.h"

namespace wb::vk {

Specialization::Specialization(const std::vector<SpecializationConstant>& constants) {
  for (const auto& c : constants) {
    entries_.push_back({c.id, static_cast<uint32_t>(values_.size() * sizeof(uint32_t)), sizeof(uint32_t)});
    values_.push_back(c.value);
  }
  info_ = {static_cast<uint32_t>(entries_.size()), entries_.data(), values_.size() * sizeof(uint32_t),
           values_.data()};
}

ShaderModule::ShaderModule(VkDevice device, const shader::CompiledShader& stage)
    : device_(device), stage_(shader::toVkStage(stage.stage)), entry_(stage.key.entry.c_str()) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = stage.spirv.size() * sizeof(uint32_t);
  ci.pCode = stage.spirv.data();
  WB_VK(vkCreateShaderModule(device, &ci, nullptr, &module_));
}

ShaderModule::~ShaderModule() {
  if (module_) vkDestroyShaderModule(device_, module_, nullptr);
}

ShaderModule::ShaderModule(ShaderModule&& other) noexcept
    : device_(other.device_), module_(other.module_), stage_(other.stage_), entry_(other.entry_) {
  other.module_ = VK_NULL_HANDLE;
}

VkPipelineShaderStageCreateInfo ShaderModule::stageInfo(const VkSpecializationInfo* specialization) const {
  VkPipelineShaderStageCreateInfo si{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  si.stage = stage_;
  si.module = module_;
  si.pName = entry_;
  si.pSpecializationInfo = specialization;
  return si;
}

}  // namespace wb::vk
