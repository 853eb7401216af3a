// Shader binding table: the size/offset arithmetic (pure, tested for many handle sizes and alignments) and
// the buffer built from a pipeline's group handles.
#pragma once
#include <cstdint>
#include <vulkan/vulkan.h>

#include "vk/resources.h"

namespace wb::vk {

struct SbtRegion {
  uint64_t offset = 0;  // from the start of the SBT buffer; a multiple of shaderGroupBaseAlignment
  uint64_t stride = 0;  // a multiple of shaderGroupHandleAlignment, >= handle size + record data
  uint64_t size = 0;    // count * stride rounded up to the base alignment (raygen: exactly one stride)
  uint32_t count = 0;
};

struct SbtLayout {
  SbtRegion raygen, miss, hit, callable;
  uint64_t totalSize = 0;
};

// Groups appear in the pipeline in this order: raygen, miss..., hit..., callable...
SbtLayout computeSbtLayout(uint32_t handleSize, uint32_t handleAlignment, uint32_t baseAlignment,
                           uint32_t missCount, uint32_t hitCount, uint32_t callableCount,
                           uint32_t recordDataSize = 0);

class ShaderBindingTable {
 public:
  ShaderBindingTable() = default;
  ShaderBindingTable(Context& ctx, VkPipeline pipeline, uint32_t missCount, uint32_t hitCount,
                     uint32_t callableCount = 0);
  void trace(Context& ctx, VkCommandBuffer cmd, uint32_t width, uint32_t height, uint32_t depth = 1) const;
  const SbtLayout& layout() const { return layout_; }
  // The pipeline's group handles as the device returned them (groupCount * handleSize bytes, in group order).
  const std::vector<uint8_t>& groupHandles() const { return handles_; }

 private:
  Buffer buffer_;
  std::vector<uint8_t> handles_;
  SbtLayout layout_;
  VkStridedDeviceAddressRegionKHR raygen_{}, miss_{}, hit_{}, callable_{};
};

}  // namespace wb::vk
