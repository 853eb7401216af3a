// Where a render pass keeps its JIT warm-up (render/jit_warmup.h), made ahead of the first hot reload.
#pragma once
#include <atomic>
#include <cstdint>
#include <exception>
#include <future>
#include <memory>
#include <mutex>
#include <utility>

#include "live/reloader.h"

namespace wb::live {

// What a warm-up of one pipeline came to.
enum class WarmOutcome {
  Warmed,  // compiled ahead (where asked) and the trial frame finished
  Renew,   // the groups could not be numbered alike (this device numbered more groups already: make another)
  Hung,    // a frame did not finish in time: the device is busy for good (the slot leaks that warm-up)
};

// makeAhead() starts making a warm-up on a low-priority thread when hot reload is set up, so that the first
// edit does not wait for it to be made (a second Vulkan instance and device, a stand-in scene and its
// pipelines). Without makeAhead() the first reload makes it.
template <class Warmup>
class WarmupSlot {
 public:
  // Starts making one with `make` unless there is one, or one is being made or used right now.
  template <class Make>
  void makeAhead(Make make) {
    std::unique_lock lock(mutex_, std::try_to_lock);
    if (!lock || warmup_ || pending_.valid()) return;
    pending_ = std::async(std::launch::async, [make = std::move(make)]() -> std::unique_ptr<Warmup> {
      lowerThreadPriority();
      return make();
    });
  }
  // Runs warm(warm-up) with the current one (waiting for one being made ahead), or with one made anew by
  // `make` when there is none, the one made ahead failed, or the current one cannot match the render device
  // any more (warm() returned Renew). Returns the outcome and the warm-up that warmed (nullptr unless
  // Warmed). A warm-up whose frame hung is never destroyed (its device cannot be waited for): the slot lets
  // go of it, and the next call makes another. Called by the hot-reload worker only.
  template <class Make, class Warm>
  std::pair<Warmup*, WarmOutcome> warmOrRenew(Make&& make, Warm&& warm) {
    std::lock_guard lock(mutex_);
    if (pending_.valid()) {
      try {
        warmup_ = pending_.get();
      } catch (const std::exception&) {
        // Made from the files as they were then (a save may have broken them since fixed): made anew below.
        warmup_.reset();
      }
    }
    auto run = [&]() -> std::pair<Warmup*, WarmOutcome> {
      const WarmOutcome o = warm(*warmup_);
      if (o == WarmOutcome::Hung) {
        (void)warmup_.release();  // its threads may run forever; the process's exit ends them
        ++hung_;
      }
      return {o == WarmOutcome::Warmed ? warmup_.get() : nullptr, o};
    };
    if (warmup_) {
      const auto r = run();
      if (r.second != WarmOutcome::Renew) return r;
    }
    warmup_ = make();
    return run();
  }
  // Warm-ups let go of because a frame hung.
  uint32_t hung() const { return hung_; }
  // Whether there is one, or one is being made (without waiting: one in use by the worker is there).
  bool present() const {
    std::unique_lock lock(mutex_, std::try_to_lock);
    return !lock || warmup_ || pending_.valid();
  }
  // Warm-ups run by the current one, without waiting (0 while one is being made or used).
  uint32_t warmups() const {
    std::unique_lock lock(mutex_, std::try_to_lock);
    return lock && warmup_ ? warmup_->warmups() : 0u;
  }

 private:
  mutable std::mutex mutex_;
  std::unique_ptr<Warmup> warmup_;
  std::atomic<uint32_t> hung_{0};
  // Declared last: destroyed first, which waits for a make in flight.
  std::future<std::unique_ptr<Warmup>> pending_;
};

}  // namespace wb::live
