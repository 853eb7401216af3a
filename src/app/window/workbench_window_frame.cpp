// The workbench window: the frame loop (events, script, hot reload, panel, trace, display, present) and the
// command buffer of one frame.
#include "app/window/workbench_window.h"

#include <cmath>
#include <cstdio>

#include <imgui.h>

namespace wb::app {

namespace {

// While converging untouched, the image is presented this often; between presents the loop only traces.
constexpr double kIdlePresentSeconds = 1.0;
// Input within this long keeps every frame presented (the user is interacting).
constexpr double kInteractionSeconds = 0.5;
// The trace time of one trace-only submission: input that arrives meanwhile waits at most this long.
constexpr double kTraceOnlyBudgetMs = 50.0;

}  // namespace

void WorkbenchWindow::readTimestamps(bool withDisplay) {
  uint64_t ts[3] = {};
  const uint32_t count = withDisplay ? 3 : 2;
  if (vkGetQueryPoolResults(session_->context().device(), queries_, 0, count, sizeof(uint64_t) * count, ts,
                            sizeof(uint64_t), VK_QUERY_RESULT_64_BIT) != VK_SUCCESS) {
    return;
  }
  const double period = session_->context().timestampPeriodNs() * 1e-6;
  traceMs_ = double(ts[1] - ts[0]) * period;
  if (withDisplay) displayMs_ = double(ts[2] - ts[1]) * period;
  if (!lastFrameHybrid_) progressive_->reportTraceTime(tracedPixels_, traceMs_);
  if (progressive_->generation() != traceGeneration_) {
    traceGeneration_ = progressive_->generation();
    traceSeconds_ = 0;
  }
  if (tracedPixels_ > 0) traceSeconds_ += traceMs_ * 1e-3;
}

void WorkbenchWindow::recordFrame(VkCommandBuffer cmd, uint32_t imageIndex, const Rect& image) {
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  WB_VK(vkBeginCommandBuffer(cmd, &bi));
  vkCmdResetQueryPool(cmd, queries_, 0, 3);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
  render::HybridRenderer* hybrid = activeHybrid();
  lastFrameHybrid_ = hybrid != nullptr;
  if (hybrid) {
    const bool run = !state_.paused && (state_.params.render.spp == 0 ||
                                        hybrid->samplesAccumulated() < state_.params.render.spp);
    tracedPixels_ = 0;
    if (run) {
      hybrid->record(cmd);
      hybrid->advance();
      tracedPixels_ = uint64_t(hybrid->settings().width) * hybrid->settings().height;
    }
  } else {
    tracedPixels_ = progressive_->record(cmd);
  }
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);

  VkClearValue clear{};
  clear.color = {{0.06f, 0.06f, 0.07f, 1.0f}};
  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = swapchain_->renderPass();
  rp.framebuffer = swapchain_->framebuffer(imageIndex);
  rp.renderArea = {{0, 0}, swapchain_->extent()};
  rp.clearValueCount = 1;
  rp.pClearValues = &clear;
  vkCmdBeginRenderPass(cmd, &rp, VK_SUBPASS_CONTENTS_INLINE);
  const auto& tracer = session_->pathTracer();
  gpu::DisplayPush push{};
  push.viewRect = {image.x, image.y, image.w, image.h};
  push.imageSize = {tracer.settings().width, tracer.settings().height};
  const bool usePreview = !hybrid && progressive_->previewValid() && progressive_->samples() == 0;
  push.previewSize =
      usePreview ? glm::uvec2(progressive_->previewImage().width(), progressive_->previewImage().height())
                 : glm::uvec2(0u);
  push.exposureScale = std::exp2(state_.params.display.exposure);
  push.tonemap = uint32_t(state_.params.display.tonemap);
  push.view =
      hybrid ? WB_VIEW_BEAUTY : state_.params.display.view;  // the debug views are the path tracer's AOVs
  push.encodeSrgb = swapchain_->formatIsSrgb() ? 0u : 1u;
  push.tracedRows = progressive_->samples() == 0 ? progressive_->cursorRow() : tracer.settings().height;
  if (hybrid) {
    push.imageSize = {hybrid->settings().width, hybrid->settings().height};
    push.tracedRows = hybrid->settings().height;
  }
  push.sceneScale = sceneRadius(session_->scene());
  push.maxVertices = float(tracer.settings().maxBounces + 1);
  if (image.w >= 1 && image.h >= 1) display_->record(cmd, push);
  gui_->render(cmd);
  vkCmdEndRenderPass(cmd);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 2);
  if (captureThisFrame_) capture_->record(cmd, *swapchain_, imageIndex);
  WB_VK(vkEndCommandBuffer(cmd));
}

bool WorkbenchWindow::traceOnlyAllowed(Clock::time_point now) const {
  using Seconds = std::chrono::duration<double>;
  if (activeHybrid() || dragging_ || state_.paused || loop_->hot().busy() || !modeSwitch_.empty())
    return false;
  if (!screenshotPath_.empty() || state_.saveRequest) return false;
  if (hasScript_ && !script_.waitingForEvent()) return false;
  if (progressive_->inPreview() || progressive_->samples() == 0 || progressive_->done()) return false;
  if (Seconds(now - lastInput_).count() < kInteractionSeconds) return false;
  return Seconds(now - lastPresent_).count() < kIdlePresentSeconds;
}

bool WorkbenchWindow::traceOnly() {
  auto& ctx = session_->context();
  progressive_->options().stopAtSamples =
      liveError_.nextCheckpoint(progressive_->samples(), progressive_->secondsSinceReset());
  const double frameBudget = progressive_->options().budgetMs;
  progressive_->options().budgetMs = std::max(frameBudget, kTraceOnlyBudgetMs);
  progressive_->beginFrame();
  if (progressive_->inPreview() || progressive_->done()) {
    progressive_->options().budgetMs = frameBudget;
    return false;
  }
  WB_VK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  WB_VK(vkBeginCommandBuffer(cmd_, &bi));
  vkCmdResetQueryPool(cmd_, queries_, 0, 3);
  vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, queries_, 0);
  lastFrameHybrid_ = false;
  tracedPixels_ = progressive_->record(cmd_);
  vkCmdWriteTimestamp(cmd_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, queries_, 1);
  WB_VK(vkEndCommandBuffer(cmd_));
  progressive_->options().budgetMs = frameBudget;
  if (tracedPixels_ == 0) return false;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  WB_VK(vkResetFences(ctx.device(), 1, &fence_));
  {
    std::lock_guard lock(ctx.queueMutex());
    WB_VK(vkQueueSubmit(ctx.queue(), 1, &si, fence_));
  }
  WB_VK(vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  readTimestamps(false);
  counters_ = session_->renderer().readCounters();
  updateLiveError();
  ++traceOnlySubmits_;
  return true;
}

bool WorkbenchWindow::nothingToDo() const {
  const bool tracing =
      activeHybrid() ? !state_.paused && (state_.params.render.spp == 0 ||
                                          activeHybrid()->samplesAccumulated() < state_.params.render.spp)
                     : !state_.paused && !progressive_->done();
  return !tracing && !loop_->hot().busy() && !dragging_ && modeSwitch_.empty() && screenshotPath_.empty() &&
         !state_.saveRequest && (!hasScript_ || script_.waitingForEvent()) && !options_.frames;
}

void WorkbenchWindow::finishFrame(Clock::time_point frameBegin) {
  auto& ctx = session_->context();
  WB_VK(vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  frameInFlight_ = false;
  readTimestamps(true);
  loop_->frameFinished(frameBegin);
  showCompletedReloads();
  // While a rebuild compiles on a CPU device, the loop rests after each frame so the compile gets most of the
  // cores: the panel and the present cost CPU time besides the trace budget.
  const auto until = loop_->restUntil(frameBegin, Clock::now(), ctx.policy().windowRestRatio);
  // Input still wakes the loop's event queue; it is handled with the next frame.
  for (auto t = Clock::now(); loop_->compiling() && t < until; t = Clock::now())
    glfwWaitEventsTimeout(std::chrono::duration<double>(until - t).count());
  counters_ = session_->renderer().readCounters();
  updateLiveError();
  updateInspection();
  if (!captureTarget_.empty()) {
    capture_->write(captureTarget_);
    std::printf("workbench: window screenshot %s\n", captureTarget_.c_str());
    std::fflush(stdout);
    captureTarget_.clear();
  }
}

bool WorkbenchWindow::traceWhileConverging(int& exitCode) {
  // Input, a rebuild or a script step ends it at once; the script's waits are checked after each submission.
  while (!frameInFlight_ && traceOnlyAllowed(Clock::now()) && traceOnly()) {
    glfwPollEvents();
    if (input_->takeActivity()) {
      lastInput_ = Clock::now();
      break;
    }
    if (hasScript_) {
      try {
        if (!script_.step(*this) || !script_.waitingForEvent()) break;
      } catch (const std::exception& e) {
        fatalScriptError_ = e.what();
        exitCode = 1;
        return false;
      }
    }
  }
  return !state_.quit;
}

bool WorkbenchWindow::stepScript(int& exitCode) {
  if (!hasScript_ || !screenshotPath_.empty()) return true;  // a requested screenshot is drawn first
  try {
    // A finished script still lets a requested screenshot reach the screen.
    return script_.step(*this) || options_.frames || !screenshotPath_.empty();
  } catch (const std::exception& e) {
    fatalScriptError_ = e.what();
    exitCode = 1;
    return false;
  }
}

bool WorkbenchWindow::drawFrame(float dt) {
  auto& ctx = session_->context();
  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window_, &fbw, &fbh);
  if (fbw == 0 || fbh == 0) {  // minimised: nothing to draw into
    glfwWaitEventsTimeout(0.1);
    return false;
  }
  if (uint32_t(fbw) != swapchain_->extent().width || uint32_t(fbh) != swapchain_->extent().height) {
    if (!swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync)) return false;
    gui_->swapchainRecreated(*swapchain_);
  }

  gui_->beginFrame();
  PanelContext pc{
      state_,
      session_->scene(),
      *progressive_,
      loop_->hot(),
      session_->library(),
      camera_,
      pick_,
      frames_,
      counters_,
      traceSeconds_,
      ctx.deviceName(),
      vk::presentModeName(swapchain_->presentMode()),
      activeHybrid() ? activeHybrid()->settings().width : session_->pathTracer().settings().width,
      activeHybrid() ? activeHybrid()->settings().height : session_->pathTracer().settings().height,
      lastSaved_,
      activeHybrid(),
      currentSamples(),
      activeHybrid() ? std::chrono::duration<double>(Clock::now() - hybridReset_).count()
                     : progressive_->secondsSinceReset(),
      &liveError_,
      modeSwitch_,
      std::chrono::duration<double>(Clock::now() - modeSwitchTimer_.requestTime()).count(),

      &inspector_};
  const float W = float(swapchain_->extent().width), H = float(swapchain_->extent().height);
  panelWidth_ = drawSidePanel(pc, W, H);
  const Rect view{panelWidth_, 0.0f, std::max(W - panelWidth_, 1.0f), H};
  drawOverlays(pc, imageRect(view));
  drawABPanel(ab_, W, H);
  applyABDecision();
  handleInput(view, dt);

  // The trace resolution follows the view beside the panel (times the resolution scale) unless --size
  // fixed it; hiding the panel (Tab) shows the same image larger instead of restarting it.
  if (state_.fixedSize) {
    progressive_->setTargetSize(uint32_t(std::lround(state_.fixedWidth * state_.resolutionScale)),
                                uint32_t(std::lround(state_.fixedHeight * state_.resolutionScale)));
  } else {
    const float traceViewWidth = std::max(W - sidePanelWidth(W), 1.0f);
    progressive_->setTargetSize(uint32_t(std::lround(traceViewWidth * state_.resolutionScale)),
                                uint32_t(std::lround(view.h * state_.resolutionScale)));
  }
  applyState();
  if (state_.saveRequest) {
    try {
      saveRender(*state_.saveRequest);
    } catch (const std::exception& e) {
      lastSaved_ = std::string("save failed: ") + e.what();
    }
    state_.saveRequest.reset();
  }
  render::HybridRenderer* hybrid = activeHybrid();
  if (hybrid && (hybrid->settings().width != progressive_->targetWidth() ||
                 hybrid->settings().height != progressive_->targetHeight())) {
    render::RenderSettings hs = state_.params.render;
    hs.width = progressive_->targetWidth();
    hs.height = progressive_->targetHeight();
    hybrid->setSettings(hs);
    ++hybridGeneration_;
    hybridReset_ = Clock::now();
  }
  if (!hybrid) {
    progressive_->options().stopAtSamples =
        liveError_.nextCheckpoint(progressive_->samples(), progressive_->secondsSinceReset());
    progressive_->beginFrame();
  }
  const auto& tracer = session_->pathTracer();
  display_->setSources({hybrid ? hybrid->outputImage().view() : tracer.accumulationImage().view(),
                        tracer.aovImage(render::Aov::Albedo).view(),
                        tracer.aovImage(render::Aov::Normal).view(),
                        tracer.aovImage(render::Aov::Info).view(), progressive_->previewImage().view(),
                        tracer.aovImage(render::Aov::Stats).view()});

  auto index = swapchain_->acquire(imageAvailable_);
  if (!index) {
    ImGui::EndFrame();
    swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync);
    gui_->swapchainRecreated(*swapchain_);
    return false;
  }
  const bool lastFrame = options_.frames && frameCount_ + 1 >= options_.frames;
  if (!screenshotPath_.empty() || (lastFrame && !options_.screenshot.empty())) {
    captureThisFrame_ = true;
    captureTarget_ = screenshotPath_.empty() ? options_.screenshot : screenshotPath_;
    screenshotPath_.clear();
  }
  const Rect image = imageRect(view);
  WB_VK(vkResetCommandBuffer(cmd_, 0));
  recordFrame(cmd_, *index, image);
  captureThisFrame_ = false;
  VkPipelineStageFlags wait = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSemaphore done = swapchain_->renderFinished(*index);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &imageAvailable_;
  si.pWaitDstStageMask = &wait;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &done;
  WB_VK(vkResetFences(ctx.device(), 1, &fence_));
  {
    std::lock_guard lock(ctx.queueMutex());
    WB_VK(vkQueueSubmit(ctx.queue(), 1, &si, fence_));
  }
  frameInFlight_ = true;
  lastPresent_ = Clock::now();
  if (!swapchain_->present(*index, done)) {
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
    swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync);
    gui_->swapchainRecreated(*swapchain_);
  }
  ++frameCount_;
  return true;
}

int WorkbenchWindow::run() {
  auto& ctx = session_->context();
  auto last = Clock::now();
  auto frameBegin = last;  // when the work of the frame in flight began (after any rest)
  int exitCode = 0;
  while (!glfwWindowShouldClose(window_) && !state_.quit) {
    glfwPollEvents();
    if (frameInFlight_) finishFrame(frameBegin);
    if (input_->takeActivity()) lastInput_ = Clock::now();
    // Converging untouched: trace without drawing or presenting until the next present is due.
    if (!traceWhileConverging(exitCode)) break;
    // Nothing to trace and nothing happening: sleep until input (or a short timeout for the panel's clocks
    // and the script's waits) instead of redrawing the same frame.
    if (!frameInFlight_ && nothingToDo() &&
        std::chrono::duration<double>(Clock::now() - lastInput_).count() > kInteractionSeconds) {
      glfwWaitEventsTimeout(0.25);
      if (input_->takeActivity()) lastInput_ = Clock::now();
    }
    const auto now = Clock::now();
    const float dt = std::chrono::duration<float>(now - last).count();
    if (frameCount_ > 0) addFrameTime(last, now);
    last = now;
    frameBegin = now;

    if (options_.frames && frameCount_ >= options_.frames) break;
    if (!stepScript(exitCode)) break;
    loop_->beginFrame();
    drawFrame(dt);
  }
  if (frameInFlight_) {
    vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
    readTimestamps(true);
    counters_ = session_->renderer().readCounters();
    if (!captureTarget_.empty()) {
      capture_->write(captureTarget_);
      std::printf("workbench: window screenshot %s\n", captureTarget_.c_str());
    }
  }
  if (!options_.statsPath.empty()) writeStats(options_.statsPath);
  std::printf("workbench: %llu frames, %u samples, frame time mean %.1f ms (p95 %.1f ms)\n",
              static_cast<unsigned long long>(frameCount_), progressive_->samples(), frames_.mean(),
              frames_.percentile(0.95f));
  if (!fatalScriptError_.empty())
    std::fprintf(stderr, "workbench: script error: %s\n", fatalScriptError_.c_str());
  return exitCode;
}

}  // namespace wb::app
