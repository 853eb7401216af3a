#include "vk/gpu_timer.h"

#include <algorithm>
#include <stdexcept>

namespace wb::vk {

GpuTimer::GpuTimer(Context& ctx, uint32_t maxScopes) : ctx_(ctx) {
  if (ctx.timestampValidBits() == 0 || maxScopes == 0) return;
  capacity_ = 2 * maxScopes;
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = capacity_;
  WB_VK(vkCreateQueryPool(ctx.device(), &qi, nullptr, &pool_));
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void GpuTimer::begin(VkCommandBuffer cmd, const std::string& pass, uint32_t samples) {
  open_ = false;
  if (!pool_ || used_ + 2 > capacity_) return;
  if (!resetRecorded_) {
    vkCmdResetQueryPool(cmd, pool_, 0, capacity_);
    resetRecorded_ = true;
  }
  // Bottom of pipe: written once the commands before it completed, so the scope starts where the pass does.
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, used_);
  pending_.push_back({pass, used_, std::max(samples, 1u)});
  used_ += 2;
  open_ = true;
}

void GpuTimer::end(VkCommandBuffer cmd) {
  if (!open_) return;
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, pending_.back().query + 1);
  open_ = false;
}

const std::vector<PassTime>& GpuTimer::collect() {
  last_.clear();
  if (pool_ && used_ > 0) {
    struct Result {
      uint64_t value, available;
    };
    std::vector<Result> results(used_);
    const VkResult r =
        vkGetQueryPoolResults(ctx_.device(), pool_, 0, used_, results.size() * sizeof(Result), results.data(),
                              sizeof(Result), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WITH_AVAILABILITY_BIT);
    if (r == VK_SUCCESS || r == VK_NOT_READY) {
      const uint32_t bits = ctx_.timestampValidBits();
      const uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1;
      const double msPerTick = double(ctx_.timestampPeriodNs()) * 1e-6;
      // Per pass: its scopes' time summed, and the samples of its longest scope (strips of one sample sum
      // to that sample; a launch of several samples is divided by them).
      for (const auto& p : pending_) {
        const Result& a = results[p.query];
        const Result& b = results[p.query + 1];
        if (!a.available || !b.available) continue;
        const double ms = double((b.value - a.value) & mask) * msPerTick;
        auto it =
            std::find_if(last_.begin(), last_.end(), [&](const PassTime& t) { return t.pass == p.pass; });
        if (it == last_.end()) it = last_.insert(last_.end(), PassTime{p.pass, 0.0, 0, 0});
        it->ms += ms;
        ++it->scopes;
        it->samples = std::max(it->samples, p.samples);
      }
      for (auto& t : last_) t.ms /= t.samples;
    }
  }
  for (const auto& t : last_) {
    auto it =
        std::find_if(totals_.begin(), totals_.end(), [&](const PassTime& x) { return x.pass == t.pass; });
    if (it == totals_.end()) {
      it = totals_.insert(totals_.end(), PassTime{t.pass, 0.0, 0, 0});
      roundMs_.emplace_back();
    }
    it->ms += t.ms;
    it->scopes += t.scopes;
    it->samples += t.samples;
    roundMs_[size_t(it - totals_.begin())].push_back(t.ms);
  }
  if (!last_.empty()) ++rounds_;
  discardRound();
  return last_;
}

void GpuTimer::discardRound() {
  pending_.clear();
  used_ = 0;
  resetRecorded_ = false;
  open_ = false;
}

void GpuTimer::resetTotals() {
  totals_.clear();
  roundMs_.clear();
  rounds_ = 0;
}

std::vector<PassTime> GpuTimer::medians() const {
  std::vector<PassTime> out;
  for (size_t i = 0; i < totals_.size(); ++i) {
    std::vector<double> v = roundMs_[i];
    std::sort(v.begin(), v.end());
    out.push_back(
        {totals_[i].pass, v.empty() ? 0.0 : v[v.size() / 2], totals_[i].scopes, totals_[i].samples});
  }
  return out;
}

double gpuSeconds(Context& ctx, const std::function<void(VkCommandBuffer)>& record) {
  GpuTimer timer(ctx, 1);
  if (!timer.supported())
    throw std::runtime_error("the device's queue has no timestamps (timestampValidBits 0)");
  ctx.submitAndWait([&](VkCommandBuffer cmd) {
    GpuTimer::Scope timed(&timer, cmd, "work");
    record(cmd);
  });
  const auto& round = timer.collect();
  if (round.empty()) throw std::runtime_error("gpuSeconds: the timestamps are not available");
  return round.front().ms * 1e-3;
}

}  // namespace wb::vk
