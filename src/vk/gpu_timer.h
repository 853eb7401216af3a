// GPU time of recorded work: timestamp queries around intervals of a command buffer. The benchmarks time the
// device this way where a submission's wall time would count the host's submit and wait (sub-millisecond
// launches on a GPU).
#pragma once
#include <cstdint>
#include <functional>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::vk {

class GpuTimer {
 public:
  explicit GpuTimer(Context& ctx, uint32_t intervals = 1);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Recording: reset() first in the command buffer, then begin(i) and end(i) around each interval's work.
  void reset(VkCommandBuffer cmd) const;
  void begin(VkCommandBuffer cmd, uint32_t interval = 0) const;
  void end(VkCommandBuffer cmd, uint32_t interval = 0) const;
  // After the command buffer completed: the interval's GPU time in seconds (waits for the queries).
  double seconds(uint32_t interval = 0) const;

 private:
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t intervals_ = 0;
  uint64_t mask_ = ~0ull;  // the queue's valid timestamp bits
};

// Records `record` between two timestamps into a fresh command buffer, submits, waits; returns its GPU
// seconds.
double gpuSeconds(Context& ctx, const std::function<void(VkCommandBuffer)>& record);

}  // namespace wb::vk
