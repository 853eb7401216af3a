#include "vk/pipeline_layout.h"

#include <algorithm>

namespace wb::vk {

PipelineLayout::PipelineLayout(Context& ctx, const shader::PipelineLayoutDesc& desc)
    : ctx_(ctx), desc_(desc) {
  uint32_t maxSet = 0;
  for (const auto& b : desc.bindings) maxSet = std::max(maxSet, b.set + 1);
  setLayouts_.resize(maxSet, VK_NULL_HANDLE);
  for (uint32_t s = 0; s < maxSet; ++s) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    std::vector<VkDescriptorBindingFlags> flags;
    for (const auto& b : desc.bindings) {
      if (b.set != s) continue;
      VkDescriptorSetLayoutBinding lb{};
      lb.binding = b.binding;
      lb.descriptorType = b.type;
      lb.descriptorCount = b.runtimeArray ? kRuntimeArrayCapacity : std::max(b.count, 1u);
      lb.stageFlags = b.stages;
      bindings.push_back(lb);
      flags.push_back(b.runtimeArray ? VK_DESCRIPTOR_BINDING_PARTIALLY_BOUND_BIT : 0);
    }
    VkDescriptorSetLayoutBindingFlagsCreateInfo fi{
        VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_BINDING_FLAGS_CREATE_INFO};
    fi.bindingCount = static_cast<uint32_t>(flags.size());
    fi.pBindingFlags = flags.data();
    VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    ci.pNext = &fi;
    ci.bindingCount = static_cast<uint32_t>(bindings.size());
    ci.pBindings = bindings.data();
    WB_VK(vkCreateDescriptorSetLayout(ctx.device(), &ci, nullptr, &setLayouts_[s]));
  }
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = maxSet;
  pci.pSetLayouts = setLayouts_.data();
  pci.pushConstantRangeCount = static_cast<uint32_t>(desc.pushConstants.size());
  pci.pPushConstantRanges = desc.pushConstants.data();
  WB_VK(vkCreatePipelineLayout(ctx.device(), &pci, nullptr, &layout_));
}

PipelineLayout::~PipelineLayout() {
  if (layout_) vkDestroyPipelineLayout(ctx_.device(), layout_, nullptr);
  for (auto l : setLayouts_) {
    if (l) vkDestroyDescriptorSetLayout(ctx_.device(), l, nullptr);
  }
}

const shader::DescriptorBinding* PipelineLayout::binding(uint32_t set, uint32_t binding) const {
  for (const auto& b : desc_.bindings) {
    if (b.set == set && b.binding == binding) return &b;
  }
  return nullptr;
}

bool PipelineLayout::compatibleWith(const shader::PipelineLayoutDesc& other) const {
  if (other.bindings.size() != desc_.bindings.size() ||
      other.pushConstants.size() != desc_.pushConstants.size()) {
    return false;
  }
  for (size_t i = 0; i < other.bindings.size(); ++i) {
    const auto &a = desc_.bindings[i], &b = other.bindings[i];
    if (a.set != b.set || a.binding != b.binding || a.type != b.type || a.count != b.count ||
        a.runtimeArray != b.runtimeArray || a.stages != b.stages) {
      return false;
    }
  }
  for (size_t i = 0; i < other.pushConstants.size(); ++i) {
    const auto &a = desc_.pushConstants[i], &b = other.pushConstants[i];
    if (a.offset != b.offset || a.size != b.size || a.stageFlags != b.stageFlags) return false;
  }
  return true;
}

const shader::DescriptorBinding* DescriptorSets::target(uint32_t set, uint32_t binding) const {
  return layout_.binding(set, binding);
}

DescriptorSets::DescriptorSets(Context& ctx, const PipelineLayout& layout) : ctx_(ctx), layout_(layout) {
  std::map<VkDescriptorType, uint32_t> counts;
  for (const auto& b : layout.desc().bindings) {
    counts[b.type] += b.runtimeArray ? kRuntimeArrayCapacity : std::max(b.count, 1u);
  }
  std::vector<VkDescriptorPoolSize> sizes;
  for (auto [type, n] : counts) sizes.push_back({type, n});
  if (sizes.empty()) sizes.push_back({VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1});
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = std::max(layout.setCount(), 1u);
  pci.poolSizeCount = static_cast<uint32_t>(sizes.size());
  pci.pPoolSizes = sizes.data();
  WB_VK(vkCreateDescriptorPool(ctx.device(), &pci, nullptr, &pool_));
  sets_.resize(layout.setCount());
  for (uint32_t s = 0; s < layout.setCount(); ++s) {
    VkDescriptorSetLayout sl = layout.setLayout(s);
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool_;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &sl;
    WB_VK(vkAllocateDescriptorSets(ctx.device(), &ai, &sets_[s]));
  }
}

DescriptorSets::~DescriptorSets() {
  if (pool_) vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
}

void DescriptorSets::writeBuffer(uint32_t set, uint32_t binding, VkBuffer buffer, VkDeviceSize size) {
  const auto* b = target(set, binding);
  if (!b) return;
  VkDescriptorBufferInfo info{buffer, 0, size};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = sets_.at(set);
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = b->type;
  w.pBufferInfo = &info;
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

void DescriptorSets::writeStorageImage(uint32_t set, uint32_t binding, VkImageView view) {
  const auto* b = target(set, binding);
  if (!b) return;
  VkDescriptorImageInfo info{VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = sets_.at(set);
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = b->type;
  w.pImageInfo = &info;
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

void DescriptorSets::writeSampledImages(uint32_t set, uint32_t binding,
                                        const std::vector<VkDescriptorImageInfo>& images) {
  const auto* b = target(set, binding);
  if (!b || images.empty()) return;
  uint32_t capacity = b->runtimeArray ? kRuntimeArrayCapacity : std::max(b->count, 1u);
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = sets_.at(set);
  w.dstBinding = binding;
  w.descriptorCount = std::min<uint32_t>(static_cast<uint32_t>(images.size()), capacity);
  w.descriptorType = b->type;
  w.pImageInfo = images.data();
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

void DescriptorSets::writeAccelerationStructure(uint32_t set, uint32_t binding,
                                                VkAccelerationStructureKHR as) {
  const auto* b = target(set, binding);
  if (!b) return;
  VkWriteDescriptorSetAccelerationStructureKHR asInfo{
      VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  asInfo.accelerationStructureCount = 1;
  asInfo.pAccelerationStructures = &as;
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.pNext = &asInfo;
  w.dstSet = sets_.at(set);
  w.dstBinding = binding;
  w.descriptorCount = 1;
  w.descriptorType = b->type;
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

const char* descriptorKindName(DescriptorKind k) {
  switch (k) {
    case DescriptorKind::Buffer:
      return "a buffer";
    case DescriptorKind::StorageImage:
      return "a storage image";
    case DescriptorKind::SampledImages:
      return "sampled images";
    default:
      return "an acceleration structure";
  }
}

bool fills(DescriptorKind k, VkDescriptorType t) {
  switch (k) {
    case DescriptorKind::Buffer:
      return t == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || t == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case DescriptorKind::StorageImage:
      return t == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    case DescriptorKind::SampledImages:
      return t == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    default:
      return t == VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  }
}

}  // namespace wb::vk
