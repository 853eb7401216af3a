// GPU time of recorded work: timestamp queries around named scopes of command buffers. A renderer brackets
// each pass it records with a GpuTimer::Scope; once the submission has finished, collect() reads the round
// back: the GPU milliseconds of each pass per sample, the scopes of one pass summed (the path tracer's strips
// of one frame) and a scope of several samples (a launch of several) divided by them. The renderers time the
// path tracer and each hybrid pass this way, the window's Presenter its trace, the work after it (the
// denoiser) and its display. The medians over rounds (a round: one batch of samples or one frame of
// Renderer::render) give
// `--stats`' and `bench`'s `pass_ms`. The benchmarks time the device this way too (gpuSeconds), where a
// submission's wall time would count the host's submit and wait.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::vk {

struct PassTime {
  std::string pass;  // the pass's key: "pathtracer", "gbuffer", "shadow_ao", "reflections", "composite", ...
  double ms = 0;     // GPU time per sample (a round: the submission's; totals: the sum over rounds)
  uint32_t scopes = 0;
  uint32_t samples = 0;  // the samples its scopes traced (a scope of one frame counts one)
};

class GpuTimer {
 public:
  // Up to `maxScopes` scopes are timed per round (more are recorded untimed).
  explicit GpuTimer(Context& ctx, uint32_t maxScopes = 64);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // False when the queue writes no timestamps: scopes time nothing.
  bool supported() const { return pool_ != VK_NULL_HANDLE; }

  // Times what is recorded into cmd between begin and end, the work of `samples` samples. Call outside a
  // render pass instance: the first scope of a round resets the round's queries there. Scopes do not nest.
  void begin(VkCommandBuffer cmd, const std::string& pass, uint32_t samples = 1);
  void end(VkCommandBuffer cmd);
  class Scope {
   public:
    Scope(GpuTimer* timer, VkCommandBuffer cmd, const std::string& pass, uint32_t samples = 1)
        : timer_(timer), cmd_(cmd) {
      if (timer_) timer_->begin(cmd_, pass, samples);
    }
    ~Scope() {
      if (timer_) timer_->end(cmd_);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    GpuTimer* timer_;
    VkCommandBuffer cmd_;
  };

  // Call once every submission holding the round's scopes has finished: the round's time per pass and
  // sample (in the order first recorded; a scope whose timestamps are not available is left out), added to
  // the totals. Starts the next round.
  const std::vector<PassTime>& collect();
  const std::vector<PassTime>& last() const { return last_; }
  // The sums of the rounds collected since resetTotals(); rounds() counts the rounds that timed anything.
  const std::vector<PassTime>& totals() const { return totals_; }
  uint32_t rounds() const { return rounds_; }
  // Each pass's median round since resetTotals() (ms: the median of its rounds' times per sample).
  std::vector<PassTime> medians() const;
  void resetTotals();
  // Forgets the round's scopes without reading them: their command buffer was never submitted.
  void discardRound();

 private:
  struct Pending {
    std::string pass;
    uint32_t query = 0;  // begin; end is query + 1
    uint32_t samples = 1;
  };
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t capacity_ = 0;  // queries
  uint32_t used_ = 0;      // queries written this round
  bool resetRecorded_ = false;
  bool open_ = false;  // a scope began and was timed
  std::vector<Pending> pending_;
  std::vector<PassTime> last_, totals_;
  std::vector<std::vector<double>> roundMs_;  // per pass of totals_, each round's ms per sample
  uint32_t rounds_ = 0;
};

// Records `record` in one scope of a fresh command buffer, submits, waits; returns its GPU seconds (throws
// when the queue writes no timestamps).
double gpuSeconds(Context& ctx, const std::function<void(VkCommandBuffer)>& record);

}  // namespace wb::vk
