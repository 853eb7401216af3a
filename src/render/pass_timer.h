// GPU time per pass. A renderer brackets each pass it records with a PassTimer::Scope (timestamps written
// before and after its commands); once the submission has finished, collect() reads the round back: the GPU
// milliseconds of each pass, the scopes of one pass summed (the path tracer's strips of one frame). Any pass
// a renderer records gets timed this way: the path tracer, each hybrid pass, the denoiser when it lands (the
// window's display pass is timed by its Presenter). The medians over rounds (a round: one sample or frame of
// Renderer::render) give `--stats`' and `bench`'s `pass_ms`: the first round, which carries the driver's
// compile of a new pipeline on some devices, does not set them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::render {

struct PassTime {
  std::string pass;  // the pass's key: "pathtracer", "gbuffer", "shadow_ao", "reflections", "composite"
  double ms = 0;     // GPU time (a round: the submission's; totals: the sum over rounds)
  uint32_t scopes = 0;
};

class PassTimer {
 public:
  // Up to `maxScopes` scopes are timed per round (more are recorded untimed).
  explicit PassTimer(vk::Context& ctx, uint32_t maxScopes = 64);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

  // False when the queue writes no timestamps: scopes time nothing.
  bool supported() const { return pool_ != VK_NULL_HANDLE; }

  // Times what is recorded into cmd between begin and end. Call outside a render pass instance: the first
  // scope of a round resets the round's queries there. Scopes do not nest.
  void begin(VkCommandBuffer cmd, const std::string& pass);
  void end(VkCommandBuffer cmd);
  class Scope {
   public:
    Scope(PassTimer* timer, VkCommandBuffer cmd, const std::string& pass) : timer_(timer), cmd_(cmd) {
      if (timer_) timer_->begin(cmd_, pass);
    }
    ~Scope() {
      if (timer_) timer_->end(cmd_);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PassTimer* timer_;
    VkCommandBuffer cmd_;
  };

  // Call once every submission holding the round's scopes has finished: the round's time per pass (in the
  // order first recorded; a scope whose timestamps are not available is left out), added to the totals.
  // Starts the next round.
  const std::vector<PassTime>& collect();
  const std::vector<PassTime>& last() const { return last_; }
  // The sums of the rounds collected since resetTotals(); rounds() counts the rounds that timed anything.
  const std::vector<PassTime>& totals() const { return totals_; }
  uint32_t rounds() const { return rounds_; }
  // Each pass's median round since resetTotals() (ms: the median of its rounds' times).
  std::vector<PassTime> medians() const;
  void resetTotals();

 private:
  struct Pending {
    std::string pass;
    uint32_t query = 0;  // begin; end is query + 1
  };
  vk::Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t capacity_ = 0;  // queries
  uint32_t used_ = 0;      // queries written this round
  bool resetRecorded_ = false;
  bool open_ = false;  // a scope began and was timed
  std::vector<Pending> pending_;
  std::vector<PassTime> last_, totals_;
  std::vector<std::vector<double>> roundMs_;  // per pass of totals_, each round's ms
  uint32_t rounds_ = 0;
};

}  // namespace wb::render
