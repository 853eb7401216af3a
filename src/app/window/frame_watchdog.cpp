#include "app/window/frame_watchdog.h"

namespace wb::app {

FrameWatchdog::FrameWatchdog(VkDevice device, std::function<void(const std::string& message)> onHang)
    : device_(device), onHang_(std::move(onHang)), thread_([this] { run(); }) {}

FrameWatchdog::~FrameWatchdog() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameWatchdog::arm(VkFence fence, std::chrono::nanoseconds limit, std::string message) {
  // Called with lock() held.
  ++generation_;
  fence_ = VK_NULL_HANDLE;
  const auto now = std::chrono::steady_clock::now();
  if (limit < std::chrono::steady_clock::time_point::max() - now) {
    fence_ = fence;
    deadline_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(limit);
    message_ = std::move(message);
  }
  changed_.notify_all();
}

void FrameWatchdog::disarm() {
  {
    std::lock_guard lock(mutex_);
    ++generation_;
    fence_ = VK_NULL_HANDLE;
  }
  changed_.notify_all();
}

void FrameWatchdog::run() {
  std::unique_lock lock(mutex_);
  while (!stop_) {
    if (fence_ == VK_NULL_HANDLE) {
      changed_.wait(lock);
      continue;
    }
    const uint64_t generation = generation_;
    if (changed_.wait_until(lock, deadline_, [&] { return stop_ || generation_ != generation; })) continue;
    // The limit has passed on the same frame. Its fence may have signalled while nobody looked (the frame
    // loop busy elsewhere): then it is not hung. A lost device is the frame loop's own wait's to report.
    const VkResult status = vkGetFenceStatus(device_, fence_);
    fence_ = VK_NULL_HANDLE;
    if (status == VK_NOT_READY) {
      const std::string message = message_;
      lock.unlock();
      onHang_(message);
      return;
    }
  }
}

}  // namespace wb::app
