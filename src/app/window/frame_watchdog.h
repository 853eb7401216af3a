#pragma once
// Watches the window's frame in flight from a thread of its own. The thread that submitted a frame may block
// in a call that waits for it before it reaches its own wait with a time limit (Presenter::waitForFence):
// lavapipe's vkQueuePresentKHR waits for the frame's rendering, so a shader that never ends would hang the
// window for good. A frame whose fence has not signalled once its limit has passed counts as hung: onHang
// gets the message the frame was armed with, on the watchdog's thread.
#include <vulkan/vulkan.h>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace wb::app {

class FrameWatchdog {
 public:
  FrameWatchdog(VkDevice device, std::function<void(const std::string& message)> onHang);
  ~FrameWatchdog();
  FrameWatchdog(const FrameWatchdog&) = delete;
  FrameWatchdog& operator=(const FrameWatchdog&) = delete;

  // The watchdog reads the fence's status, and vkResetFences and vkQueueSubmit need the fence to themselves:
  // hold this lock around them and around arm().
  std::unique_lock<std::mutex> lock() { return std::unique_lock(mutex_); }
  // The frame just submitted with `fence` is hung if it has not finished `limit` from now (the maximum:
  // never).
  void arm(VkFence fence, std::chrono::nanoseconds limit, std::string message);
  // The frame's fence was seen signalled (or its wait gave up by itself): nothing to watch.
  void disarm();

 private:
  void run();

  VkDevice device_;
  std::function<void(const std::string&)> onHang_;
  std::mutex mutex_;
  std::condition_variable changed_;
  VkFence fence_ = VK_NULL_HANDLE;  // the armed frame's, or none
  std::chrono::steady_clock::time_point deadline_;
  std::string message_;
  uint64_t generation_ = 0;  // counts arm() and disarm(): a wait that ends on another generation looks again
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace wb::app
