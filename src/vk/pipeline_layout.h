// Descriptor set layouts, the pipeline layout and descriptor sets, all built from reflected shader bindings:
// nothing about bindings is written twice by hand.
#pragma once
#include <map>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

#include "shader/library.h"
#include "shader/types.h"
#include "vk/context.h"

namespace wb::vk {

// Capacity given to runtime arrays (unsized sampler2D textures[] etc.).
constexpr uint32_t kRuntimeArrayCapacity = 1024;

class PipelineLayout {
 public:
  PipelineLayout(Context& ctx, const shader::PipelineLayoutDesc& desc);
  ~PipelineLayout();
  PipelineLayout(const PipelineLayout&) = delete;
  PipelineLayout& operator=(const PipelineLayout&) = delete;

  VkPipelineLayout handle() const { return layout_; }
  const shader::PipelineLayoutDesc& desc() const { return desc_; }
  VkDescriptorSetLayout setLayout(uint32_t set) const { return setLayouts_.at(set); }
  uint32_t setCount() const { return static_cast<uint32_t>(setLayouts_.size()); }
  // The reflected binding at set/binding, or nullptr if no stage uses it.
  const shader::DescriptorBinding* binding(uint32_t set, uint32_t binding) const;
  // True when both layouts would accept the same descriptor sets and push constants.
  bool compatibleWith(const shader::PipelineLayoutDesc& other) const;

 private:
  Context& ctx_;
  shader::PipelineLayoutDesc desc_;
  std::vector<VkDescriptorSetLayout> setLayouts_;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
};

// What a write fills (the descriptor types each kind of write can fill: fills()).
enum class DescriptorKind { Buffer, StorageImage, SampledImages, AccelerationStructure };
const char* descriptorKindName(DescriptorKind kind);  // "a buffer", "a storage image", ...
bool fills(DescriptorKind kind, VkDescriptorType type);

// One descriptor set per layout set, written by set and binding number (render::Pass finds the numbers by
// the names the shaders declare). Writes for bindings that no stage uses are skipped (they are not in the
// reflected layout).
class DescriptorSets {
 public:
  DescriptorSets(Context& ctx, const PipelineLayout& layout);
  ~DescriptorSets();
  DescriptorSets(const DescriptorSets&) = delete;
  DescriptorSets& operator=(const DescriptorSets&) = delete;

  VkDescriptorSet set(uint32_t i) const { return sets_.at(i); }
  const std::vector<VkDescriptorSet>& sets() const { return sets_; }

  void writeBuffer(uint32_t set, uint32_t binding, VkBuffer buffer, VkDeviceSize size = VK_WHOLE_SIZE);
  void writeStorageImage(uint32_t set, uint32_t binding, VkImageView view);
  void writeSampledImages(uint32_t set, uint32_t binding, const std::vector<VkDescriptorImageInfo>& images);
  void writeAccelerationStructure(uint32_t set, uint32_t binding, VkAccelerationStructureKHR as);

 private:
  const shader::DescriptorBinding* target(uint32_t set, uint32_t binding) const;

  Context& ctx_;
  const PipelineLayout& layout_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
};

}  // namespace wb::vk
