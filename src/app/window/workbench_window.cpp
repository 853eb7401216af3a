// The workbench window: set-up and tear-down, hot reload targets, access to the renderer of the current mode.
#include "app/window/workbench_window.h"

#include "common/env.h"

#include <algorithm>
#include <stdexcept>

#include "common/paths.h"

namespace wb::app {

float sceneRadius(const scene::Scene& s) {
  return std::max(0.5f * glm::length(s.bounds.max - s.bounds.min), 1e-3f);
}

WorkbenchWindow::WorkbenchWindow(GLFWwindow* window, const WindowOptions& o) : window_(window), options_(o) {
  state_.params = o.render.params;
  state_.params.render.aov = true;  // the debug views read the AOV images
  // The target spp: --spp when given, else keep refining.
  state_.params.render.spp = o.render.flags.given("spp") ? o.render.params.render.spp : 0;
  state_.resolutionScale = o.scale;
  state_.fixedSize = o.sizeGiven;
  state_.fixedWidth = o.render.params.render.width;
  state_.fixedHeight = o.render.params.render.height;
  state_.vsync = !o.noVsync;
  state_.referencePath = o.reference;

  uint32_t extCount = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&extCount);
  if (!exts) throw std::runtime_error("GLFW found no Vulkan surface support on this display");
  render::SessionOptions so;
  so.scenePath = o.render.scene;
  so.settings = state_.params.render;
  so.settings.width = so.settings.height = 64;  // resized to the view once the window is laid out
  so.context.deviceName = o.render.device;
  so.context.instanceExtensions.assign(exts, exts + extCount);
  so.context.presentation = true;
  so.hybrid = o.render.params.hybrid;  // the mode is applied with the first frame, at the trace size
  session_ = std::make_unique<render::RenderSession>(so);
  auto& ctx = session_->context();

  makeSwapchain();
  display_ =
      std::make_unique<DisplayPass>(ctx, session_->library(), swapchain_->renderPass(), swapchain_->format());
  input_ = std::make_unique<InputEvents>(window_);  // first: ImGui's backend chains its callbacks to these
  gui_ = std::make_unique<GuiLayer>(ctx, window_, *swapchain_, o.imguiIni);
  progressive_ = std::make_unique<ProgressiveTracer>(ctx, session_->pathTracer());
  capture_ = std::make_unique<SwapchainCapture>(ctx);

  state_.materials = session_->scene().materials;
  state_.lights = session_->scene().lights;
  applied_ = state_;
  camera_.reset(session_->scene().camera, sceneRadius(session_->scene()));

  live::EditLoopOptions lo;
  lo.ab = ab_.enabled;
  loop_ = std::make_unique<live::EditLoop>(*session_, lo);  // every renderer, the modes made later too
  loop_->addPass(display_->pass());
  loop_->start([] { glfwPostEmptyEvent(); });  // ends a rest or an idle wait: the build is committed at once
  applyMode(true);  // the mode the window opens in (--mode) is there from the first frame

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
  VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
  qi.queryCount = 3;
  WB_VK(vkCreateQueryPool(ctx.device(), &qi, nullptr, &queries_));

  for (const auto& s : o.sets) {
    const auto nameValue = render::splitAssignment(s);
    if (!nameValue) throw std::invalid_argument("--set: expected NAME=VALUE, got '" + s + "'");
    applySetting(state_, nameValue->first, nameValue->second);
  }
  if (!o.scriptPath.empty()) {
    script_ = Script::fromFile(o.scriptPath);
    hasScript_ = true;
  }
}

void WorkbenchWindow::makeSwapchain() {
  auto& ctx = session_->context();
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
    swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync);
  } catch (const std::exception& e) {
    swapchain_.reset();  // destroys the surface too
    throw PresentationUnavailable(e.what() + device);
  }
}

WorkbenchWindow::~WorkbenchWindow() {
  if (loop_) loop_->hot().stop();
  if (!session_) return;
  VkDevice d = session_->context().device();
  session_->context().waitIdle();
  if (queries_) vkDestroyQueryPool(d, queries_, nullptr);
  if (imageAvailable_) vkDestroySemaphore(d, imageAvailable_, nullptr);
  if (fence_) vkDestroyFence(d, fence_, nullptr);
  if (pool_) vkDestroyCommandPool(d, pool_, nullptr);
  capture_.reset();
  gui_.reset();
  display_.reset();
  swapchain_.reset();
  progressive_.reset();
  ab_.installed.clear();  // the old pipelines kept for Revert
  loop_.reset();          // its passes are the session's renderers' and the display's
  session_.reset();
}

void WorkbenchWindow::scriptCommand(const std::string& name) {
  if (name == "reset_camera") state_.resetCamera = true;
  if (name == "reset") state_.resetAccumulation = true;
  if (name == "reload") state_.reloadShaders = true;
  if (name == "quit") state_.quit = true;
  if (name == "ab_revert") ab_.revertRequested = true;
  if (name == "ab_accept") ab_.acceptRequested = true;
}

Rect WorkbenchWindow::imageRect(const Rect& view) const {
  const auto& s = session_->pathTracer().settings();
  const float tw = float(progressive_->targetWidth()), th = float(progressive_->targetHeight());
  (void)s;
  const float scale = std::min(view.w / tw, view.h / th);
  const float w = std::max(1.0f, std::floor(tw * scale)), h = std::max(1.0f, std::floor(th * scale));
  return {std::floor(view.x + (view.w - w) * 0.5f), std::floor(view.y + (view.h - h) * 0.5f), w, h};
}

void WorkbenchWindow::applyMode(bool wait) {
  if (session_->mode() == state_.params.mode) {
    if (!modeSwitch_.empty()) modeSwitchTimer_.cancelled();  // switched back before the other mode was ready
    modeSwitch_.clear();
    return;
  }
  render::RenderSettings s = state_.params.render;
  s.width = progressive_->targetWidth();
  s.height = progressive_->targetHeight();
  // The other mode's renderer is made off the frame loop; the current mode keeps drawing until it is ready.
  const std::string name = render::renderModeName(state_.params.mode);
  if (!wait && modeSwitch_ != name) {  // a switch the user waits for: timed for the stats
    modeSwitch_ = name;
    modeSwitchTimer_.requested(name, Clock::now());
  }
  if (!wait && !session_->modeReady(state_.params.mode)) {
    session_->prepareMode(state_.params.mode, s);
    return;
  }
  session_->setMode(state_.params.mode, s);
  // A hybrid mode starts its accumulation with the switch: its frames, elapsed time and noise estimate count
  // from here, not from its last reset (before an earlier switch away, or at startup).
  if (auto* h = activeHybrid()) {
    h->resetAccumulation();
    ++hybridGeneration_;
    hybridReset_ = Clock::now();
  }
  if (!modeSwitch_.empty()) modeSwitchTimer_.tookEffect(Clock::now());
  modeSwitch_.clear();
}

void WorkbenchWindow::scriptSwitchMode(const std::string& mode) {
  applySetting(state_, "mode", mode);
  applyState();  // starts the switch; the frames that follow complete it
}

void WorkbenchWindow::addFrameTime(Clock::time_point begin, Clock::time_point end) {
  frames_.add(std::chrono::duration<float, std::milli>(end - begin).count());
  modeSwitchTimer_.frame(begin, end);
}

uint32_t WorkbenchWindow::currentSamples() const {
  if (const auto* h = activeHybrid()) return h->samplesAccumulated();
  return progressive_->samples();
}

eval::ImageRGBA WorkbenchWindow::currentImage() {
  return session_->image();
}

void WorkbenchWindow::updateLiveError() {
  // Called when no frame is in flight. Only whole samples count: the path tracer's accumulation is read when
  // a sample has just finished (the progressive tracer stops at sample ends when a checkpoint is due).
  auto* h = activeHybrid();
  if (!h && (progressive_->inPreview() || progressive_->cursorRow() != 0)) return;
  if (h && h->samplesAccumulated() < hybridFramesSeen_) ++hybridGeneration_;  // reset by a pipeline install
  if (h) hybridFramesSeen_ = h->samplesAccumulated();
  const uint64_t generation = h ? hybridGeneration_ * 2 + 1 : progressive_->generation() * 2;
  if (generation != errorGeneration_) {
    liveError_.restart();
    errorGeneration_ = generation;
  }
  const uint32_t n = currentSamples();
  const double seconds = h ? std::chrono::duration<double>(Clock::now() - hybridReset_).count()
                           : progressive_->secondsSinceReset();
  if (liveError_.wants(n, seconds)) liveError_.add(currentImage(), n, seconds);
}

}  // namespace wb::app
