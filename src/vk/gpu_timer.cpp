#include "vk/gpu_timer.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace wb::vk {

GpuTimer::GpuTimer(Context& ctx, uint32_t intervals) : ctx_(ctx), intervals_(intervals) {
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &families, nullptr);
  std::vector<VkQueueFamilyProperties> props(families);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physicalDevice(), &families, props.data());
  const uint32_t bits = props.at(ctx.queueFamily()).timestampValidBits;
  if (bits == 0) throw std::runtime_error("the device's queue has no timestamps (timestampValidBits 0)");
  mask_ = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = 2 * intervals;
  WB_VK(vkCreateQueryPool(ctx.device(), &qi, nullptr, &pool_));
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void GpuTimer::reset(VkCommandBuffer cmd) const {
  vkCmdResetQueryPool(cmd, pool_, 0, 2 * intervals_);
}

void GpuTimer::begin(VkCommandBuffer cmd, uint32_t interval) const {
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_, 2 * interval);
}

void GpuTimer::end(VkCommandBuffer cmd, uint32_t interval) const {
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 2 * interval + 1);
}

double GpuTimer::seconds(uint32_t interval) const {
  uint64_t ts[2] = {0, 0};
  WB_VK(vkGetQueryPoolResults(ctx_.device(), pool_, 2 * interval, 2, sizeof(ts), ts, sizeof(uint64_t),
                              VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const uint64_t ticks = (ts[1] - ts[0]) & mask_;
  return double(ticks) * double(ctx_.timestampPeriodNs()) * 1e-9;
}

double gpuSeconds(Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
  GpuTimer timer(ctx);
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    timer.begin(cmd);
    record(cmd);
    timer.end(cmd);
  });
  return timer.seconds();
}

}  // namespace wb::vk
