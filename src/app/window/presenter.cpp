#include "app/window/presenter.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <atomic>
#include <cstdio>
#include <thread>
#include <unistd.h>

#include "common/env.h"
#include "vk/check.h"

namespace wb::app {

Presenter::Presenter(vk::Context& ctx, shader::ShaderLibrary& library, GLFWwindow* window, bool vsync,
                     const std::string& imguiIni)
    : ctx_(ctx), window_(window), vsync_(vsync) {
  const std::string device = " (" + ctx.deviceName() + ")";
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  if (glfwCreateWindowSurface(ctx.instance(), window_, nullptr, &surface) != VK_SUCCESS)
    throw PresentationUnavailable("cannot create a Vulkan surface for the window" + device);
  try {
    swapchain_ = std::make_unique<vk::Swapchain>(ctx, surface);
  } catch (const std::exception& e) {
    vkDestroySurfaceKHR(ctx.instance(), surface, nullptr);
    throw PresentationUnavailable(e.what() + device);
  }
  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window_, &fbw, &fbh);
  try {
    if (env::enabled("WB_SIMULATE_NO_PRESENT"))
      throw std::runtime_error("vkCreateSwapchainKHR failed with VK_ERROR_UNKNOWN (WB_SIMULATE_NO_PRESENT)");
    swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), vsync_);
  } catch (const std::exception& e) {
    swapchain_.reset();  // destroys the surface too
    throw PresentationUnavailable(e.what() + device);
  }
  display_ = std::make_unique<DisplayPass>(ctx, library, swapchain_->renderPass(), swapchain_->format());
  gui_ = std::make_unique<GuiLayer>(ctx, window_, *swapchain_, imguiIni);
  capture_ = std::make_unique<SwapchainCapture>(ctx);

  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = ctx.queueFamily();
  WB_VK(vkCreateCommandPool(ctx.device(), &pi, nullptr, &pool_));
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  WB_VK(vkAllocateCommandBuffers(ctx.device(), &ai, &cmd_));
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  WB_VK(vkCreateFence(ctx.device(), &fi, nullptr, &fence_));
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  WB_VK(vkCreateSemaphore(ctx.device(), &si, nullptr, &imageAvailable_));
  timer_ = std::make_unique<vk::GpuTimer>(ctx, 3);
  watchdog_ = std::make_unique<FrameWatchdog>(ctx.device(), [](const std::string& m) { endForHang(m); });
}

void Presenter::endForHang(const std::string& message) {
  static std::atomic_flag ended = ATOMIC_FLAG_INIT;
  if (ended.test_and_set())
    for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
  std::fprintf(stderr, "workbench: error: %s\n", message.c_str());
  std::fflush(stdout);
  std::fflush(stderr);
  ::_exit(4);
}

Presenter::~Presenter() {
  if (inFlight_) WB_VK(vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
  watchdog_.reset();
  inFlight_ = false;
  ctx_.waitIdle();
  VkDevice d = ctx_.device();
  timer_.reset();
  if (imageAvailable_) vkDestroySemaphore(d, imageAvailable_, nullptr);
  if (fence_) vkDestroyFence(d, fence_, nullptr);
  if (pool_) vkDestroyCommandPool(d, pool_, nullptr);
  capture_.reset();
  gui_.reset();
  display_.reset();
  swapchain_.reset();
}

void Presenter::setVsync(bool vsync) {
  if (vsync == vsync_) return;
  vsync_ = vsync;
  recreate();
}

void Presenter::recreate() {
  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window_, &fbw, &fbh);
  // The frame in flight may use the old swapchain; it stays in flight for finish() to account for.
  if (inFlight_) waitForFence();
  if (swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), vsync_)) gui_->swapchainRecreated(*swapchain_);
}

bool Presenter::beginFrame() {
  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window_, &fbw, &fbh);
  if (fbw == 0 || fbh == 0) {  // minimised: nothing to draw into
    glfwWaitEventsTimeout(0.1);
    return false;
  }
  if (uint32_t(fbw) != swapchain_->extent().width || uint32_t(fbh) != swapchain_->extent().height) {
    if (!swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), vsync_)) return false;
    gui_->swapchainRecreated(*swapchain_);
  }
  gui_->beginFrame();
  return true;
}

void Presenter::readTimestamps() {
  for (const auto& t : timer_->collect()) {
    if (t.pass == "trace") traceMs_ = t.ms;
    if (t.pass == "after_trace") afterTraceMs_ = t.ms;
    if (t.pass == "display") displayMs_ = t.ms;
  }
  timer_->resetTotals();  // only the last frame's times are read: no history to keep
}

void Presenter::waitForFence() {
  const auto limit = frameLimit_ ? frameLimit_() : std::chrono::nanoseconds::max();
  const uint64_t ns = limit == std::chrono::nanoseconds::max() ? UINT64_MAX : uint64_t(limit.count());
  const VkResult r = vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, ns);
  if (r == VK_SUCCESS) watchdog_->disarm();
  if (r == VK_TIMEOUT) {
    FrameHang hang("a frame did not finish");
    hang.seconds = std::chrono::duration<double>(limit).count();
    throw hang;
  }
  WB_VK(r);
}

void Presenter::submit(const VkSubmitInfo& si) {
  const auto limit = watchdogLimit_ ? watchdogLimit_() : std::chrono::nanoseconds::max();
  const double seconds = std::chrono::duration<double>(limit).count();
  std::string message = hangMessage_ ? hangMessage_(seconds) : "a frame did not finish within its limit";
  auto watching = watchdog_->lock();
  WB_VK(vkResetFences(ctx_.device(), 1, &fence_));
  {
    std::lock_guard lock(ctx_.queueMutex());
    WB_VK(vkQueueSubmit(ctx_.queue(), 1, &si, fence_));
  }
  watchdog_->arm(fence_, limit, std::move(message));
}

bool Presenter::finish() {
  if (!inFlight_) return false;
  waitForFence();
  inFlight_ = false;
  readTimestamps();
  if (!captureTarget_.empty()) {
    capture_->write(captureTarget_);
    std::printf("workbench: window screenshot %s\n", captureTarget_.c_str());
    std::fflush(stdout);
    captureTarget_.clear();
  }
  return true;
}

bool Presenter::traceOnly(const TraceRecorder& trace) {
  finish();
  WB_VK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  WB_VK(vkBeginCommandBuffer(cmd_, &bi));
  {
    vk::GpuTimer::Scope scope(timer_.get(), cmd_, "trace");
    tracedPixels_ = trace(cmd_);
  }
  WB_VK(vkEndCommandBuffer(cmd_));
  if (tracedPixels_ == 0) {
    timer_->discardRound();
    return false;
  }
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  submit(si);
  inFlight_ = true;
  finish();
  return true;
}

bool Presenter::present(const TraceRecorder& trace, const AfterTraceRecorder& afterTrace,
                        const gpu::DisplayPush& push, const std::string& screenshot) {
  auto index = swapchain_->acquire(imageAvailable_);
  if (!index) {
    ImGui::EndFrame();
    recreate();
    return false;
  }
  WB_VK(vkResetCommandBuffer(cmd_, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  WB_VK(vkBeginCommandBuffer(cmd_, &bi));
  {
    vk::GpuTimer::Scope scope(timer_.get(), cmd_, "trace");
    tracedPixels_ = trace(cmd_);
  }
  {
    vk::GpuTimer::Scope scope(timer_.get(), cmd_, "after_trace");
    afterTrace(cmd_);
  }
  {
    // Around the whole render pass instance: a scope begins and ends outside one.
    vk::GpuTimer::Scope scope(timer_.get(), cmd_, "display");
    VkClearValue clear{};
    clear.color = {{0.06f, 0.06f, 0.07f, 1.0f}};
    VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    rp.renderPass = swapchain_->renderPass();
    rp.framebuffer = swapchain_->framebuffer(*index);
    rp.renderArea = {{0, 0}, swapchain_->extent()};
    rp.clearValueCount = 1;
    rp.pClearValues = &clear;
    vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
    if (push.viewRect.z >= 1 && push.viewRect.w >= 1) display_->record(cmd_, push);
    gui_->render(cmd_);
    vkCmdEndRenderPass(cmd_);
  }
  if (!screenshot.empty()) {
    capture_->record(cmd_, *swapchain_, *index);
    captureTarget_ = screenshot;
  }
  WB_VK(vkEndCommandBuffer(cmd_));

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
  submit(si);
  inFlight_ = true;
  if (!swapchain_->present(*index, done)) recreate();
  return true;
}

}  // namespace wb::app
