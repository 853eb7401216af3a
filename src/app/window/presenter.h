// What the window puts on screen and how: the swapchain of the window's surface, the display pass, the ImGui
// layer, screenshots, and one command buffer in flight at a time with GPU timestamps around its trace, the
// work after the trace (the denoiser) and its display. A frame records the session's trace (a callback), the
// work after it (another callback), then the display pass and the panel into the swapchain's render pass,
// submits and presents; a trace-only submission records the trace alone.
#pragma once
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "app/window/capture.h"
#include "app/window/display_pass.h"
#include "app/window/frame_watchdog.h"
#include "app/window/gui_layer.h"
#include "vk/gpu_timer.h"
#include "vk/swapchain.h"

struct GLFWwindow;

namespace wb::app {

// The device cannot present to the window (no surface, no queue that presents, or the swapchain cannot be
// made, as with NVIDIA's driver on an X server without its display support): the command renders headless
// instead, saying why.
struct PresentationUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A submission did not finish within the frame limit (Presenter::setFrameLimit): the device cannot stop it.
struct FrameHang : std::runtime_error {
  using std::runtime_error::runtime_error;
  double seconds = 0;
};

class Presenter {
 public:
  // Throws PresentationUnavailable when the device cannot present to `window`.
  Presenter(vk::Context& ctx, shader::ShaderLibrary& library, GLFWwindow* window, bool vsync,
            const std::string& imguiIni);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // How long a submission may take before it counts as hung: `limit` for the waits, counted from when they
  // begin (FrameHang thrown), `watchdogLimit` for the watchdog, counted from the submission.
  void setFrameLimit(std::function<std::chrono::nanoseconds()> limit,
                     std::function<std::chrono::nanoseconds()> watchdogLimit) {
    frameLimit_ = std::move(limit);
    watchdogLimit_ = std::move(watchdogLimit);
  }
  // What the user reads when a submission counts as hung (given the limit in seconds). Asked at each
  // submission, on the frame loop's thread: the watchdog (FrameWatchdog), which says it when the frame loop
  // is blocked in a call that waits for the hung frame, runs on its own.
  void setHangMessage(std::function<std::string(double seconds)> message) {
    hangMessage_ = std::move(message);
  }
  // Says `message` on stderr and ends the process with status 4: no driver here cancels a running shader, and
  // the device cannot be closed while it runs. The first caller ends it; a second (the frame loop's own wait
  // and the watchdog at once) waits for that.
  [[noreturn]] static void endForHang(const std::string& message);

  DisplayPass& display() { return *display_; }
  const vk::Swapchain& swapchain() const { return *swapchain_; }
  GuiLayer& gui() { return *gui_; }
  void setVsync(bool vsync);

  // Records the trace into the command buffer (returns the pixels it traced).
  using TraceRecorder = std::function<uint64_t(VkCommandBuffer)>;
  // Records what a shown frame does after its trace (the denoiser), timed apart from it: the trace's time
  // paces the trace alone.
  using AfterTraceRecorder = std::function<void(VkCommandBuffer)>;
  // A frame: the trace, the work after it, the display pass with `push` (when the image rectangle is not
  // empty) and the ImGui panel, submitted and presented. `screenshot`: the presented image is written there
  // once the frame finished. False when nothing was presented (minimised, or the swapchain had to be made
  // anew).
  bool present(const TraceRecorder& trace, const AfterTraceRecorder& afterTrace, const gpu::DisplayPush& push,
               const std::string& screenshot);
  // A submission of the trace alone, waited for. False when it traced nothing.
  bool traceOnly(const TraceRecorder& trace);
  // The ImGui frame begins (before the panels are drawn); a resized framebuffer remakes the swapchain first.
  // False when there is nothing to draw into (minimised).
  bool beginFrame();
  // Waits for the frame in flight, if any; reads its timestamps and writes its screenshot. Returns whether
  // one was in flight.
  bool finish();
  bool frameInFlight() const { return inFlight_; }

  // The last finished submission: pixels traced, trace GPU time (ms); the last shown frame: the GPU time of
  // the work after its trace and of its display (ms).
  uint64_t tracedPixels() const { return tracedPixels_; }
  double traceMs() const { return traceMs_; }
  double afterTraceMs() const { return afterTraceMs_; }
  double displayMs() const { return displayMs_; }

 private:
  void recreate();
  // The finished submission's scope times: trace, after_trace and display (a trace-only one: trace).
  void readTimestamps();
  // Waits for the submission in flight within the frame limit; throws FrameHang past it.
  void waitForFence();
  // Submits cmd_ with fence_ and arms the watchdog with the frame limit.
  void submit(const VkSubmitInfo& si);

  vk::Context& ctx_;
  GLFWwindow* window_;
  bool vsync_;
  std::unique_ptr<vk::Swapchain> swapchain_;
  std::unique_ptr<DisplayPass> display_;
  std::unique_ptr<GuiLayer> gui_;
  std::unique_ptr<SwapchainCapture> capture_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore imageAvailable_ = VK_NULL_HANDLE;
  std::unique_ptr<vk::GpuTimer> timer_;  // the submission's scopes: trace, after_trace, display
  bool inFlight_ = false;
  std::string captureTarget_;
  uint64_t tracedPixels_ = 0;
  double traceMs_ = 0, afterTraceMs_ = 0, displayMs_ = 0;
  std::function<std::chrono::nanoseconds()> frameLimit_, watchdogLimit_;
  std::function<std::string(double)> hangMessage_;
  std::unique_ptr<FrameWatchdog> watchdog_;  // after fence_: it reads the fence until it is destroyed
};

}  // namespace wb::app
