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

// What a renderer writes at a binding (the descriptor types each kind of write fills).
enum class DescriptorKind { Buffer, StorageImage, SampledImages, AccelerationStructure };
struct ProvidedBinding {
  uint32_t set = 0, binding = 0;
  DescriptorKind kind = DescriptorKind::Buffer;
};

// One descriptor set per layout set; writes are addressed by binding number (from the shared header), and
// writes for bindings that no stage uses are skipped (they are not in the reflected layout). Every write
// asked for is recorded (requested()): what the renderer provides, checked against a new program's bindings
// before its pipeline is built (requireProvided).
class DescriptorSets {
 public:
  DescriptorSets(Context& ctx, const PipelineLayout& layout);
  // A recorder: no descriptor sets, the writes are only recorded.
  explicit DescriptorSets(Context& ctx);
  ~DescriptorSets();
  DescriptorSets(const DescriptorSets&) = delete;
  DescriptorSets& operator=(const DescriptorSets&) = delete;

  VkDescriptorSet set(uint32_t i) const { return sets_.at(i); }
  const std::vector<VkDescriptorSet>& sets() const { return sets_; }

  void writeBuffer(uint32_t set, uint32_t binding, VkBuffer buffer, VkDeviceSize size = VK_WHOLE_SIZE);
  void writeStorageImage(uint32_t set, uint32_t binding, VkImageView view);
  void writeSampledImages(uint32_t set, uint32_t binding, const std::vector<VkDescriptorImageInfo>& images);
  void writeAccelerationStructure(uint32_t set, uint32_t binding, VkAccelerationStructureKHR as);

  const std::vector<ProvidedBinding>& requested() const { return requested_; }

 private:
  const shader::DescriptorBinding* target(uint32_t set, uint32_t binding, DescriptorKind kind);

  Context& ctx_;
  const PipelineLayout* layout_ = nullptr;  // null for a recorder
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::vector<VkDescriptorSet> sets_;
  std::vector<ProvidedBinding> requested_;
};

// Throws shader::CompileError when `build` uses a binding that `provided` does not fill, or fills with
// another kind of descriptor: one diagnostic per binding, at the file:line that declares it, naming
// `renderer`. A program that passes binds every descriptor its pipeline reads (no
// VUID-vkCmdTraceRaysKHR-None-02699).
void requireProvided(const shader::ShaderLibrary::ProgramBuild& build,
                     const std::vector<ProvidedBinding>& provided, const std::string& renderer);

}  // namespace wb::vk
