// The live workbench without its window: what a user asks for (SessionState: every parameter, live material
// and light edits, the inspected pixel, the A/B comparison's Revert/Accept) applied to the renderers at frame
// boundaries, whatever the mode. It owns the render session (device, scene, a renderer per mode, made off the
// loop on a mode switch), the edit loop (hot reload, A/B), the path tracer's progressive tracing (strips
// within a budget, preview levels), the shader specialisation for the scene and the edits, the path
// inspector's records and the running error. The window (src/app/window) presents it: swapchain, display
// pass, panels and input; tests drive it headless.
//
// Per frame, on the render thread: apply() what changed, beginFrame(), recordTrace() into the frame's command
// buffer, submit, frameFinished() once it has finished.
#pragma once
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/image.h"
#include "eval/live_error.h"
#include "live/ab_state.h"
#include "live/edit_loop.h"
#include "live/instruments.h"
#include "live/mode_switch_timer.h"
#include "live/pixel_inspection.h"
#include "live/session_state.h"
#include "render/progressive.h"
#include "render/render_session.h"

namespace wb::live {

// What the display shows of the current frame (the storage images in GENERAL layout, and their sizes).
struct DisplayFrame {
  VkImageView radiance = VK_NULL_HANDLE;  // linear radiance of the mode shown
  VkImageView albedo = VK_NULL_HANDLE, normal = VK_NULL_HANDLE, info = VK_NULL_HANDLE, stats = VK_NULL_HANDLE;
  VkImageView cost = VK_NULL_HANDLE;  // the path tracer's cost AOV
  VkImageView preview = VK_NULL_HANDLE;
  // The denoised radiance (the path tracer with denoise on, once recordDenoise() records it), else null.
  VkImageView denoised = VK_NULL_HANDLE;
  glm::uvec2 imageSize{1u};
  glm::uvec2 previewSize{0u};  // 0: no preview under the rows not traced yet
  uint32_t tracedRows = 0;     // rows of the current sample traced so far (the rest shows the preview)
  bool debugViews = true;      // the path tracer's AOVs exist for the image shown (its debug views apply)
  float maxVertices = 1.0f;    // the path tracer's vertices per path (the bounces view's scale)
};

class LiveSession {
 public:
  using Clock = std::chrono::steady_clock;
  struct Options {
    render::SessionOptions session;                // its settings, hybrid settings and mode come from `state`
    SessionState state;                            // the first state (parameters, scale, --size, reference)
    std::vector<std::filesystem::path> watchDirs;  // empty: shaders/
  };

  explicit LiveSession(Options options);
  ~LiveSession();
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  render::RenderSession& render() { return *session_; }
  const render::RenderSession& render() const { return *session_; }
  EditLoop& loop() { return *loop_; }
  const EditLoop& loop() const { return *loop_; }
  // Starts watching the shaders; `onReady` (optional) wakes a loop that sleeps between frames.
  void start(std::function<void()> onReady = {});

  // What the user asks for. Edit it at will; apply() (a frame boundary) makes the renderers match it.
  SessionState& state() { return state_; }
  const SessionState& state() const { return state_; }
  // NAME=VALUE as the window's --set and the script's `set` give it; applied at once (a mode switch starts).
  void set(const std::string& name, const std::string& value);
  void setCamera(const render::CameraState& camera);
  // The trace size the view asks for: the view beside the panel times the resolution scale, or --size.
  void setTraceSize(uint32_t width, uint32_t height);
  // At a frame boundary (no frame in flight): applies what changed in state(); restarts accumulation when a
  // change alters the image; starts or completes a mode switch (`waitForMode`: at once, else made off the
  // loop while the current mode draws on).
  void apply(bool waitForMode = false);

  // The frame: beginFrame() installs reloads and decides this frame's trace; recordTrace() records it (the
  // path tracer's strips within the trace budget, a whole frame of a hybrid mode) and returns the pixels it
  // traces (0: nothing to trace); traceTimed() takes its measured GPU time; frameFinished() when the frame's
  // work is done (completed reloads, counters, running error, inspector records).
  void beginFrame();
  uint64_t recordTrace(VkCommandBuffer cmd);
  // The denoiser of a shown frame (path tracer, denoise on). planDenoise() after beginFrame() decides whether
  // this frame denoises: once the accumulation holds a whole sample, at its first frame that traces; then,
  // as new samples arrive, when their count has doubled since the last run and the denoiser stays within
  // kDenoiseShareDoubling of the time (the image improves most early on) unless the user gave input in the
  // last kDenoiseQuietSeconds (a run delays the next input's frame by its whole time), else within
  // kDenoiseShare; and at once when paused (nothing traces meanwhile). The last output is shown in between
  // (of the same image, with fewer samples). While the first sample is traced in strips, the raw rows are
  // shown. recordDenoise() after recordTrace() records the planned run; denoiseTimed() takes its measured GPU
  // time. displayFrame().denoised is the output when it is (or becomes in this frame) the current image's.
  static constexpr double kDenoiseShare = 0.03, kDenoiseShareDoubling = 0.1, kDenoiseQuietSeconds = 2.0;
  void planDenoise(bool frameTraces, double secondsSinceInput);
  void recordDenoise(VkCommandBuffer cmd);
  void denoiseTimed(double ms);
  bool denoiseShown() const;
  uint64_t denoiseRuns() const { return denoiseRuns_; }
  // The view is denoised as the settings ask: denoise off, a hybrid mode, or the denoiser's output of the
  // current image recorded in a frame (paused: of every sample the image holds).
  bool denoisedAsAsked() const;
  void traceTimed(uint64_t pixels, double ms);
  void frameFinished(Clock::time_point frameBegin);
  // After a trace-only submission finished (no reload completes with it): counters and running error.
  void traceOnlyFinished();
  // Trace-only submissions while converging untouched: beginTraceOnly() prepares one with at least `budgetMs`
  // of tracing (false: nothing to trace that way; recordTrace then records it).
  bool converging() const;
  bool beginTraceOnly(double budgetMs);
  // A frame interval of the render loop (times a mode switch from its request).
  void frameInterval(Clock::time_point begin, Clock::time_point end) { modeSwitchTimer_.frame(begin, end); }

  // What is shown.
  render::RenderMode mode() const { return session_->mode(); }
  const std::string& modeSwitch() const { return modeSwitch_; }  // the mode being made (empty: none)
  double modeSwitchSeconds() const;
  const ModeSwitchTimer& modeSwitches() const { return modeSwitchTimer_; }
  DisplayFrame displayFrame() const;
  uint32_t traceWidth() const { return progressive_->targetWidth(); }
  uint32_t traceHeight() const { return progressive_->targetHeight(); }
  // The renderer's image size (the path tracer's may be a preview level's).
  uint32_t imageWidth() const { return session_->renderer().settings().width; }
  uint32_t imageHeight() const { return session_->renderer().settings().height; }
  uint32_t samples() const;        // finished samples (path tracer) or frames (hybrid modes)
  const char* sampleUnit() const;  // "samples" or "frames"
  // The mode's effective parameters where they differ from what was asked ("in use: sun angle ..."; "").
  std::string modeInUse() const;
  // Whether the mode shows a preview after a change (the path tracer's progressive levels).
  bool previews() const { return !session_->hybrid(); }
  bool inPreview() const;
  bool tracing() const;  // there is something left to trace (not paused, target not reached)
  // The image shown has something traced (a sample's strips, a preview, a hybrid frame): a frame may be drawn
  // without tracing.
  bool imageStarted() const;
  bool busy() const;  // a reload or a mode switch is in progress
  // While another mode is shown: the path tracer's samples that going back to it resumes (0: none, or its
  // image is out of date).
  uint32_t pathTracerSamplesKept() const;
  double secondsSinceReset() const;
  uint64_t resets() const;
  double gpuTraceSeconds() const { return traceSeconds_; }  // since the last restart
  const gpu::Counters& counters() const { return counters_; }
  const render::ProgressiveTracer& progressive() const { return *progressive_; }
  const render::HybridRenderer* hybrid() const { return session_->hybrid(); }
  const PixelInspection& inspection() const { return inspection_; }
  // Per-pass GPU times of the last submission, the cost summary of the cost views, the asserts' failures.
  const Instruments& instruments() const { return instruments_; }
  const eval::LiveError& liveError() const { return liveError_; }
  ABState& ab() { return ab_; }
  const ABState& ab() const { return ab_; }
  eval::ImageRGBA image();  // linear radiance of what is shown (waits for the device)

  // The path inspector: a click on the trace image at `rel` (0..1 in both axes) picks the pixel.
  void inspectAt(glm::vec2 rel);
  // The inspected pixel's records as of the last finished frame, read again now (a script step: the device
  // is idle).
  const PixelInspection& inspectionNow();

 private:
  void applyMode(bool wait);
  bool applyInspection();
  void applyAB();
  void updateLiveError();
  void updateInspection();
  void restartHybrid();

  SessionState state_;
  SessionState applied_;  // what the renderers have
  std::unique_ptr<render::RenderSession> session_;
  std::unique_ptr<EditLoop> loop_;
  std::unique_ptr<render::ProgressiveTracer> progressive_;
  bool cameraChanged_ = false;
  // The last pixel a click picked and the trace size it was picked at.
  struct Picked {
    glm::uvec2 pixel, size;
  };
  std::optional<Picked> picked_;
  bool pathTracerStale_ = false;  // something that alters its image changed while another mode was shown
  render::CameraState camera_;
  // The hybrid modes' accumulation: restarts (a changed generation restarts the running error), when the
  // last one was, and how many frames the last check saw (fewer: a pipeline install restarted it).
  uint64_t hybridGeneration_ = 0, hybridResets_ = 0;
  uint32_t hybridFramesSeen_ = 0;
  Clock::time_point hybridReset_ = Clock::now();
  bool lastTraceHybrid_ = false;
  // The denoiser's output: of which accumulation (generation, size, samples), when it was recorded and what
  // it cost; whether this frame denoises (planDenoise) and whether the frame in flight did.
  struct Denoised {
    uint64_t generation = ~0ull;
    uint32_t width = 0, height = 0, samples = 0;
    Clock::time_point at{};
    double ms = 0;
  } denoised_;
  bool denoiseThisFrame_ = false, denoiseInFlight_ = false;
  uint64_t denoiseRuns_ = 0;
  bool denoiseValid() const;
  // The old pipeline's accumulation parked for an edit's review, taken back (Revert, an identical image):
  // resumed when it is of the size traced now (true); else it waits for its size in place of the other
  // size's parked accumulation. `keepOtherSize`: the other size's accumulation stays valid (an identical
  // image) rather than being the rejected pipeline's.
  bool takeBackReviewed(bool keepOtherSize);
  uint64_t traceGeneration_ = 0;
  double traceSeconds_ = 0;
  gpu::Counters counters_{};
  std::string modeSwitch_;
  ModeSwitchTimer modeSwitchTimer_;
  PixelInspection inspection_;
  Instruments instruments_;
  eval::LiveError liveError_;
  std::string referenceTried_;
  uint64_t errorGeneration_ = ~0ull;
  ABState ab_;
};

}  // namespace wb::live
