#include "vk/sbt.h"

#include <cstring>
#include <stdexcept>
#include <vector>

namespace wb::vk {

SbtLayout computeSbtLayout(uint32_t handleSize, uint32_t handleAlignment, uint32_t baseAlignment,
                           uint32_t missCount, uint32_t hitCount, uint32_t callableCount,
                           uint32_t recordDataSize) {
  if (handleSize == 0 || handleAlignment == 0 || baseAlignment == 0) {
    throw std::invalid_argument("SBT: handle size and alignments must be non-zero");
  }
  if ((handleAlignment & (handleAlignment - 1)) || (baseAlignment & (baseAlignment - 1))) {
    throw std::invalid_argument("SBT: alignments must be powers of two");
  }
  const uint64_t stride = alignUp(uint64_t(handleSize) + recordDataSize, handleAlignment);
  SbtLayout l;
  uint64_t offset = 0;
  auto place = [&](SbtRegion& r, uint32_t count, bool raygen) {
    r.count = count;
    r.stride = count ? (raygen ? alignUp(stride, baseAlignment) : stride) : 0;
    r.offset = count ? offset : 0;
    r.size = count ? (raygen ? r.stride : alignUp(count * r.stride, baseAlignment)) : 0;
    offset = alignUp(offset + r.size, baseAlignment);
  };
  place(l.raygen, 1, true);
  place(l.miss, missCount, false);
  place(l.hit, hitCount, false);
  place(l.callable, callableCount, false);
  l.totalSize = offset;
  return l;
}

ShaderBindingTable::ShaderBindingTable(Context& ctx, VkPipeline pipeline, uint32_t missCount,
                                       uint32_t hitCount, uint32_t callableCount) {
  const auto& rt = ctx.rayTracing();
  layout_ = computeSbtLayout(rt.handleSize, rt.handleAlignment, rt.baseAlignment, missCount, hitCount,
                             callableCount);
  const uint32_t groupCount = 1 + missCount + hitCount + callableCount;
  std::vector<uint8_t> handles(size_t(groupCount) * rt.handleSize);
  WB_VK(ctx.vkGetRayTracingShaderGroupHandlesKHR(ctx.device(), pipeline, 0, groupCount, handles.size(),
                                                 handles.data()));
  // Over-allocate by one base alignment so the start can be aligned whatever the allocation gives.
  buffer_ = Buffer(ctx, layout_.totalSize + rt.baseAlignment,
                   VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  const uint64_t base = alignUp(buffer_.address(), rt.baseAlignment);
  const uint64_t shift = base - buffer_.address();
  std::vector<uint8_t> data(layout_.totalSize, 0);
  uint32_t group = 0;
  auto fill = [&](const SbtRegion& r) {
    for (uint32_t i = 0; i < r.count; ++i, ++group) {
      std::memcpy(data.data() + r.offset + i * r.stride, handles.data() + size_t(group) * rt.handleSize,
                  rt.handleSize);
    }
  };
  fill(layout_.raygen);
  fill(layout_.miss);
  fill(layout_.hit);
  fill(layout_.callable);
  buffer_.upload(data.data(), data.size(), shift);
  auto region = [&](const SbtRegion& r) {
    VkStridedDeviceAddressRegionKHR out{};
    if (r.count) out = {base + r.offset, r.stride, r.size};
    return out;
  };
  raygen_ = region(layout_.raygen);
  miss_ = region(layout_.miss);
  hit_ = region(layout_.hit);
  callable_ = region(layout_.callable);
  handles_ = std::move(handles);
}

void ShaderBindingTable::trace(Context& ctx, VkCommandBuffer cmd, uint32_t width, uint32_t height,
                               uint32_t depth) const {
  ctx.vkCmdTraceRaysKHR(cmd, &raygen_, &miss_, &hit_, &callable_, width, height, depth);
}

}  // namespace wb::vk
