// The live workbench window's application object (internal to src/app/window): owns the render session, the
// swapchain, the display pass, the panel and the hot reload, and runs the frame loop. Its parts:
// workbench_window.cpp (set-up, renderer access), workbench_window_state.cpp (panel state -> renderers,
// input), workbench_window_frame.cpp (the frame loop and its command buffer), workbench_window_report.cpp
// (stats JSON, saved renders). window_command.cpp parses the command line and opens the window.
#pragma once
#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "app/render_options.h"
#include "app/window/ab_panel.h"
#include "app/window/camera_controller.h"
#include "app/window/capture.h"
#include "app/window/display_pass.h"
#include "app/window/frame_stats.h"
#include "app/window/gui_layer.h"
#include "app/window/input_events.h"
#include "app/window/mode_switch_timer.h"
#include "app/window/panels.h"
#include "app/window/pixel_picker.h"
#include "app/window/progressive.h"
#include "app/window/script.h"
#include "app/window/workbench_state.h"
#include "eval/live_error.h"
#include "live/edit_loop.h"
#include "render/render_session.h"
#include "vk/swapchain.h"

namespace wb::app {

struct WindowOptions {
  RenderOptions render;
  bool sizeGiven = false;
  std::string windowSize = "1280x720";
  uint32_t windowWidth = 1280, windowHeight = 720;
  uint64_t frames = 0;
  std::string screenshot, statsPath, scriptPath, reference, imguiIni;
  std::vector<std::string> sets;
  float scale = 0.5f;
  bool noVsync = false;
};

// Half the diagonal of the scene's bounds (at least 1e-3): the orbit camera's radius, the depth view's scale.
float sceneRadius(const scene::Scene& s);

// The window opened but the device cannot present to it (no surface, no queue that presents, or the swapchain
// cannot be made, as with NVIDIA's driver on an X server without its display support): the command renders
// headless instead, saying why.
struct PresentationUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class WorkbenchWindow : public ScriptHost {
  using Clock = std::chrono::steady_clock;

 public:
  WorkbenchWindow(GLFWwindow* window, const WindowOptions& o);
  ~WorkbenchWindow() override;
  int run();

  // ScriptHost
  void scriptSet(const std::string& name, const std::string& value) override {
    applySetting(state_, name, value);
    applyState();  // at a frame boundary: what the next script line sees is the new state
    if (state_.params.mode != session_->mode()) {
      applyMode(true);
      applyState();
    }
  }
  void scriptScreenshot(const std::string& path) override { screenshotPath_ = path; }
  // Saved when the line runs (the device is idle at a script step): a `quit` after it cannot lose it, and a
  // failure ends the script.
  void scriptSave(const std::string& base) override { saveRender(base); }
  void scriptStats(const std::string& path) override { writeStats(path); }
  void scriptOrbit(float dx, float dy) override {
    CameraInput in;
    in.dragRotate = {dx, dy};
    if (camera_.update(in)) cameraChanged_ = true;
  }
  void scriptCommand(const std::string& name) override;
  void scriptResize(int width, int height) override { glfwSetWindowSize(window_, width, height); }
  void scriptInspect(const std::string& path) override;  // workbench_window_inspect.cpp
  void scriptSwitchMode(const std::string& mode) override;
  bool modeSwitchPending() const override { return !modeSwitch_.empty(); }
  size_t reloadCount() const override { return loop_->hot().history().size(); }
  uint32_t samples() const override {
    if (activeHybrid()) return activeHybrid()->samplesAccumulated();
    return progressive_->inPreview() ? 0 : progressive_->samples();
  }

 private:
  // The window surface and its swapchain; throws PresentationUnavailable when the device cannot present.
  void makeSwapchain();
  // The A/B comparison (workbench_window_ab.cpp): the edit loop compares a reload that installed pipelines
  // after its first frame (when the comparison is on); the panel shows it, and its Revert/Accept are applied
  // at a frame boundary.
  void showCompletedReloads();
  void applyABDecision();
  void applyState();
  void handleInput(const Rect& view, float dt);
  void saveRender(std::string base);
  void writeStats(const std::string& path);
  nlohmann::json statsJson();
  nlohmann::json parametersJson();
  Rect imageRect(const Rect& view) const;
  void recordFrame(VkCommandBuffer cmd, uint32_t imageIndex, const Rect& image);
  // The frame loop's parts (workbench_window_frame.cpp): waiting for the frame in flight and what needs the
  // device idle; tracing without presenting while converging untouched (false: quit); one script step (false:
  // the session ends); laying out, recording, submitting and presenting one frame (false: nothing presented).
  void finishFrame(Clock::time_point frameBegin);
  bool traceWhileConverging(int& exitCode);
  bool stepScript(int& exitCode);
  bool drawFrame(float dt);
  // A frame interval of the loop, for the frame statistics and the mode switch being timed.
  void addFrameTime(Clock::time_point begin, Clock::time_point end);
  // Reads the last submission's GPU times: trace only, or trace and display.
  void readTimestamps(bool withDisplay);
  // Whether the loop may trace without drawing or presenting: converging at full resolution, no input for a
  // moment, no rebuild in flight, no script command waiting for frames, and the last present recent enough.
  bool traceOnlyAllowed(Clock::time_point now) const;
  // One submission of trace strips without the panel, the display pass or a present. Returns false when it
  // traced nothing.
  bool traceOnly();
  // Whether the next frame has nothing new to show (nothing to trace, no input, no rebuild, no script step).
  bool nothingToDo() const;
  // The hybrid renderer of the current mode (nullptr when path tracing).
  render::HybridRenderer* activeHybrid() const { return session_->hybrid(); }
  // Makes the state's mode the session's (its renderer is made on first use, at the trace size): at once with
  // `wait`, otherwise once a worker has made it (the current mode draws meanwhile).
  void applyMode(bool wait = false);
  uint32_t currentSamples() const;  // finished samples (path tracer) or frames (hybrid modes)
  eval::ImageRGBA currentImage();   // linear radiance of what is shown (waits for the device)
  void updateLiveError();
  // The path inspector (workbench_window_inspect.cpp): the state's pixel to the path tracer (true when that
  // restarted accumulation), the records read after a frame, a click on the image picking the pixel.
  bool applyInspection();
  void updateInspection();
  void inspectClick(const Rect& image, glm::vec2 at);

  GLFWwindow* window_;
  WindowOptions options_;
  WorkbenchState state_;
  WorkbenchState applied_;  // what the renderer has
  std::unique_ptr<render::RenderSession> session_;
  std::unique_ptr<vk::Swapchain> swapchain_;
  std::unique_ptr<DisplayPass> display_;
  std::unique_ptr<InputEvents> input_;  // before gui_: ImGui's callbacks chain to its
  std::unique_ptr<GuiLayer> gui_;
  std::unique_ptr<live::EditLoop> loop_;
  std::unique_ptr<ProgressiveTracer> progressive_;
  ABView ab_;
  std::unique_ptr<SwapchainCapture> capture_;
  uint64_t hybridGeneration_ = 0;
  uint64_t hybridResets_ = 0;  // accumulation restarts while a hybrid mode was shown
  uint32_t hybridFramesSeen_ = 0;
  Clock::time_point hybridReset_ = Clock::now();
  bool lastFrameHybrid_ = false;
  eval::LiveError liveError_;
  std::string referenceTried_;
  uint64_t errorGeneration_ = ~0ull;
  CameraController camera_;
  bool cameraChanged_ = true;
  std::optional<PickResult> pick_;
  InspectorView inspector_;
  bool pickPinned_ = false;
  glm::vec2 lastMouse_{-1.0f};
  glm::vec2 pressMouse_{0.0f};
  bool dragging_ = false;
  int dragButton_ = -1;
  uint64_t keyPressesHandled_ = 0;
  Script script_;
  bool hasScript_ = false;
  std::string screenshotPath_;
  bool captureThisFrame_ = false;
  std::string captureTarget_;
  std::string lastSaved_;
  std::string fatalScriptError_;

  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore imageAvailable_ = VK_NULL_HANDLE;
  VkQueryPool queries_ = VK_NULL_HANDLE;
  bool frameInFlight_ = false;
  uint64_t tracedPixels_ = 0;
  double traceMs_ = 0, displayMs_ = 0, traceSeconds_ = 0;
  uint64_t traceGeneration_ = 0;
  gpu::Counters counters_{};
  FrameStats frames_;
  uint64_t frameCount_ = 0;
  uint64_t traceOnlySubmits_ = 0;
  std::string modeSwitch_;  // the mode being made off the frame loop (empty: none)
  // Mode switches made off the frame loop, as the stats report them: the longest frame interval from the
  // request to the new mode's second frame (its first traces included).
  ModeSwitchTimer modeSwitchTimer_;
  Clock::time_point lastPresent_ = Clock::now();
  Clock::time_point lastInput_ = Clock::now();
  float panelWidth_ = 0;
};

}  // namespace wb::app
