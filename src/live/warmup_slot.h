// Where a render pass keeps its JIT warm-up (render/jit_warmup.h), made ahead of the first hot reload.
#pragma once
#include <cstdint>
#include <exception>
#include <future>
#include <memory>
#include <mutex>

#include "live/reloader.h"

namespace wb::live {

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
  // any more (its device numbered more groups already: warm() returned false). Returns the warm-up that
  // warmed, or nullptr. Called by the hot-reload worker only.
  template <class Make, class Warm>
  Warmup* warmOrRenew(Make&& make, Warm&& warm) {
    std::lock_guard lock(mutex_);
    if (pending_.valid()) {
      try {
        warmup_ = pending_.get();
      } catch (const std::exception&) {
        // Made from the files as they were then (a save may have broken them since fixed): made anew below.
        warmup_.reset();
      }
    }
    if (warmup_ && warm(*warmup_)) return warmup_.get();
    warmup_ = make();
    return warm(*warmup_) ? warmup_.get() : nullptr;
  }
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
  // Declared last: destroyed first, which waits for a make in flight.
  std::future<std::unique_ptr<Warmup>> pending_;
};

}  // namespace wb::live
