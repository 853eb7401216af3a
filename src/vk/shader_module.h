// What every pipeline kind makes from a compiled stage: its VkShaderModule (destroyed with the object), the
// stage info that points at it with the stage's own SPIR-V entry point, and specialisation constants in the
// form Vulkan takes them.
#pragma once
#include <cstdint>
#include <vector>
#include <vulkan/vulkan.h>

#include "shader/types.h"

namespace wb::vk {

struct SpecializationConstant {
  uint32_t id = 0;
  uint32_t value = 0;
};

// 32-bit constants, each at its own offset; info() is null when there are none. Not copyable: the info points
// into the object.
class Specialization {
 public:
  explicit Specialization(const std::vector<SpecializationConstant>& constants);
  Specialization(const Specialization&) = delete;
  Specialization& operator=(const Specialization&) = delete;
  const VkSpecializationInfo* info() const { return entries_.empty() ? nullptr : &info_; }

 private:
  std::vector<VkSpecializationMapEntry> entries_;
  std::vector<uint32_t> values_;
  VkSpecializationInfo info_{};
};

// `stage` must outlive the object's stageInfo() use (the entry point name is the stage's own string).
class ShaderModule {
 public:
  ShaderModule(VkDevice device, const shader::CompiledShader& stage);
  ~ShaderModule();
  ShaderModule(ShaderModule&& other) noexcept;
  ShaderModule& operator=(ShaderModule&&) = delete;
  ShaderModule(const ShaderModule&) = delete;
  ShaderModule& operator=(const ShaderModule&) = delete;

  VkPipelineShaderStageCreateInfo stageInfo(const VkSpecializationInfo* specialization = nullptr) const;

 private:
  VkDevice device_;
  VkShaderModule module_ = VK_NULL_HANDLE;
  VkShaderStageFlagBits stage_;
  const char* entry_;
};

}  // namespace wb::vk
