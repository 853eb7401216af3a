#include "app/window/window_command.h"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include "app/hybrid_json.h"
#include "app/reload_log.h"
#include "app/render_options.h"
#include "app/render_session.h"
#include "app/window/camera_controller.h"
#include "app/window/capture.h"
#include "app/window/display_pass.h"
#include "app/window/frame_stats.h"
#include "app/window/gui_layer.h"
#include "app/window/panels.h"
#include "app/window/pixel_picker.h"
#include "app/window/progressive.h"
#include "app/window/script.h"
#include "app/window/workbench_state.h"
#include "common/paths.h"
#include "eval/live_error.h"
#include "render/hot_reload.h"
#include "vk/swapchain.h"

namespace wb::app {
namespace {

using Clock = std::chrono::steady_clock;

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

const std::vector<std::string> kWindowValueFlags = {"--frames", "--screenshot", "--stats", "--script",
                                                    "--set",    "--window",     "--scale", "--imgui-ini"};
const std::vector<std::string> kWindowBoolFlags = {"--no-vsync"};

float sceneRadius(const scene::Scene& s) {
  return std::max(0.5f * glm::length(s.bounds.max - s.bounds.min), 1e-3f);
}

std::string timestampName() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y%m%d_%H%M%S", std::localtime(&t));
  return buf;
}

class WorkbenchWindow : public ScriptHost {
 public:
  WorkbenchWindow(GLFWwindow* window, const WindowOptions& o);
  ~WorkbenchWindow() override;
  int run();

  // ScriptHost
  void scriptSet(const std::string& name, const std::string& value) override {
    applySetting(state_, name, value);
    applyState();  // at a frame boundary: what the next script line sees is the new state
  }
  void scriptScreenshot(const std::string& path) override { screenshotPath_ = path; }
  void scriptSave(const std::string& base) override { state_.saveRequest = base; }
  void scriptStats(const std::string& path) override { writeStats(path); }
  void scriptOrbit(float dx, float dy) override {
    CameraInput in;
    in.dragRotate = {dx, dy};
    if (camera_.update(in)) cameraChanged_ = true;
  }
  void scriptCommand(const std::string& name) override;
  void scriptResize(int width, int height) override { glfwSetWindowSize(window_, width, height); }
  size_t reloadCount() const override { return hot_->history().size(); }
  uint32_t samples() const override {
    if (activeHybrid()) return activeHybrid()->framesAccumulated();
    return progressive_->inPreview() ? 0 : progressive_->samples();
  }

 private:
  void registerHotReload();
  void applyState();
  void handleInput(const Rect& view, float dt);
  void saveRender(std::string base);
  void writeStats(const std::string& path);
  nlohmann::json statsJson();
  nlohmann::json parametersJson();
  Rect imageRect(const Rect& view) const;
  void recordFrame(VkCommandBuffer cmd, uint32_t imageIndex, const Rect& image);
  void readTimestamps();
  // The hybrid renderer of the current mode (nullptr when path tracing); made on first use.
  render::HybridRenderer* activeHybrid() const;
  render::HybridRenderer* ensureHybrid();
  const render::GpuEnvironment& currentEnvironment() const;
  uint32_t currentSamples() const;  // finished samples (path tracer) or frames (hybrid modes)
  eval::ImageRGBA currentImage();   // linear radiance of what is shown (waits for the device)
  void updateLiveError();

  GLFWwindow* window_;
  WindowOptions options_;
  WorkbenchState state_;
  WorkbenchState applied_;  // what the renderer has
  std::unique_ptr<RenderSession> session_;
  std::unique_ptr<vk::Swapchain> swapchain_;
  std::unique_ptr<DisplayPass> display_;
  std::unique_ptr<GuiLayer> gui_;
  std::unique_ptr<render::HotReload> hot_;
  std::unique_ptr<ProgressiveTracer> progressive_;
  std::unique_ptr<render::GpuEnvironment> environment_;  // replaces the session's after an env change
  std::unique_ptr<SwapchainCapture> capture_;
  // [0] hybrid, [1] reflections; kept once made (their hot reload targets point at them).
  std::array<std::unique_ptr<render::HybridRenderer>, 2> hybrids_;
  uint64_t hybridGeneration_ = 0;
  uint64_t hybridResets_ = 0;  // accumulation restarts while a hybrid mode was shown
  uint32_t hybridFramesSeen_ = 0;
  Clock::time_point hybridReset_ = Clock::now();
  bool lastFrameHybrid_ = false;
  eval::LiveError liveError_;
  std::string referenceTried_;
  uint64_t errorGeneration_ = ~0ull;
  std::vector<shader::ShaderLibrary::ProgramId> hotTargets_;
  CameraController camera_;
  bool cameraChanged_ = true;
  std::optional<PickResult> pick_;
  bool pickPinned_ = false;
  glm::vec2 lastMouse_{-1.0f};
  glm::vec2 pressMouse_{0.0f};
  bool dragging_ = false;
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
  bool f12Down_ = false, f5Down_ = false, tabDown_ = false;
  float panelWidth_ = 0;
};

WorkbenchWindow::WorkbenchWindow(GLFWwindow* window, const WindowOptions& o) : window_(window), options_(o) {
  state_.settings = o.render.settings;
  state_.settings.aov = true;  // the debug views read the AOV images
  state_.resolutionScale = o.scale;
  state_.fixedSize = o.sizeGiven;
  state_.fixedWidth = o.render.settings.width;
  state_.fixedHeight = o.render.settings.height;
  state_.vsync = !o.noVsync;
  state_.targetSpp = 0;
  state_.mode = o.render.mode;
  state_.hybrid = o.render.hybrid;
  state_.referencePath = o.reference;

  uint32_t extCount = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&extCount);
  if (!exts) throw std::runtime_error("GLFW found no Vulkan surface support on this display");
  SessionOptions so;
  so.scenePath = o.render.scene;
  so.settings = state_.settings;
  so.settings.width = so.settings.height = 64;  // resized to the view once the window is laid out
  so.context.deviceName = o.render.device;
  so.context.instanceExtensions.assign(exts, exts + extCount);
  so.context.presentation = true;
  session_ = std::make_unique<RenderSession>(so);
  auto& ctx = session_->context();

  VkSurfaceKHR surface = VK_NULL_HANDLE;
  if (glfwCreateWindowSurface(ctx.instance(), window_, nullptr, &surface) != VK_SUCCESS)
    throw std::runtime_error("cannot create a Vulkan surface for the window");
  swapchain_ = std::make_unique<vk::Swapchain>(ctx, surface);
  int fbw = 0, fbh = 0;
  glfwGetFramebufferSize(window_, &fbw, &fbh);
  swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync);
  display_ = std::make_unique<DisplayPass>(ctx, session_->library(), swapchain_->renderPass());
  gui_ = std::make_unique<GuiLayer>(ctx, window_, *swapchain_, o.imguiIni);
  progressive_ = std::make_unique<ProgressiveTracer>(ctx, session_->pathTracer());
  capture_ = std::make_unique<SwapchainCapture>(ctx);

  state_.materials = session_->scene().materials;
  state_.lights = session_->scene().lights;
  applied_ = state_;
  camera_.reset(session_->scene().camera, sceneRadius(session_->scene()));

  hot_ = std::make_unique<render::HotReload>(session_->library(),
                                             std::vector<std::filesystem::path>{shaderDir()});
  registerHotReload();
  hot_->start();

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
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--set: expected NAME=VALUE, got '" + s + "'");
    applySetting(state_, s.substr(0, eq), s.substr(eq + 1));
  }
  if (!o.scriptPath.empty()) {
    script_ = Script::fromFile(o.scriptPath);
    hasScript_ = true;
  }
}

WorkbenchWindow::~WorkbenchWindow() {
  if (hot_) hot_->stop();
  if (!session_) return;
  VkDevice d = session_->context().device();
  vkDeviceWaitIdle(d);
  if (queries_) vkDestroyQueryPool(d, queries_, nullptr);
  if (imageAvailable_) vkDestroySemaphore(d, imageAvailable_, nullptr);
  if (fence_) vkDestroyFence(d, fence_, nullptr);
  if (pool_) vkDestroyCommandPool(d, pool_, nullptr);
  capture_.reset();
  gui_.reset();
  display_.reset();
  swapchain_.reset();
  progressive_.reset();
  hot_.reset();
  for (auto& h : hybrids_) h.reset();
  auto& tracer = session_->pathTracer();
  (void)tracer;
  session_.reset();  // the tracer goes before environment_
  environment_.reset();
}

void WorkbenchWindow::registerHotReload() {
  auto& tracer = session_->pathTracer();
  if (std::find(hotTargets_.begin(), hotTargets_.end(), tracer.program()) == hotTargets_.end()) {
    tracer.addHotReloadTarget(*hot_);
    hotTargets_.push_back(tracer.program());
  }
  DisplayPass* display = display_.get();
  if (std::find(hotTargets_.begin(), hotTargets_.end(), display->program()) == hotTargets_.end()) {
    hot_->addTarget(display->program(),
                    {"display",
                     [display](const shader::ShaderLibrary::ProgramBuild& b) -> std::shared_ptr<void> {
                       return std::shared_ptr<PreparedDisplayPipeline>(display->prepare(b));
                     },
                     [display](std::shared_ptr<void> p) {
                       auto prepared = std::static_pointer_cast<PreparedDisplayPipeline>(p);
                       auto owned = std::make_unique<PreparedDisplayPipeline>();
                       owned->layout = std::move(prepared->layout);
                       owned->pipeline = prepared->pipeline;
                       owned->device = prepared->device;
                       prepared->pipeline = VK_NULL_HANDLE;
                       display->commit(std::move(owned));
                     }});
    hotTargets_.push_back(display->program());
  }
}

void WorkbenchWindow::scriptCommand(const std::string& name) {
  if (name == "reset_camera") state_.resetCamera = true;
  if (name == "reset") state_.resetAccumulation = true;
  if (name == "reload") state_.reloadShaders = true;
  if (name == "quit") state_.quit = true;
}

Rect WorkbenchWindow::imageRect(const Rect& view) const {
  const auto& s = session_->pathTracer().settings();
  const float tw = float(progressive_->targetWidth()), th = float(progressive_->targetHeight());
  (void)s;
  const float scale = std::min(view.w / tw, view.h / th);
  const float w = std::max(1.0f, std::floor(tw * scale)), h = std::max(1.0f, std::floor(th * scale));
  return {std::floor(view.x + (view.w - w) * 0.5f), std::floor(view.y + (view.h - h) * 0.5f), w, h};
}

render::HybridRenderer* WorkbenchWindow::activeHybrid() const {
  switch (state_.mode) {
    case render::RenderMode::Hybrid:
      return hybrids_[0].get();
    case render::RenderMode::Reflections:
      return hybrids_[1].get();
    default:
      return nullptr;
  }
}

const render::GpuEnvironment& WorkbenchWindow::currentEnvironment() const {
  return environment_ ? *environment_ : session_->environment();
}

render::HybridRenderer* WorkbenchWindow::ensureHybrid() {
  if (state_.mode == render::RenderMode::PathTrace) return nullptr;
  auto& slot = hybrids_[state_.mode == render::RenderMode::Hybrid ? 0 : 1];
  if (!slot) {
    render::RenderSettings s = state_.settings;
    s.width = progressive_->targetWidth();
    s.height = progressive_->targetHeight();
    slot = std::make_unique<render::HybridRenderer>(session_->context(), session_->library(),
                                                    session_->gpuScene(), session_->scene(),
                                                    currentEnvironment(), s, state_.mode, state_.hybrid);
    slot->setCamera(camera_.state());
    slot->setLights(state_.lights);
    slot->addHotReloadTargets(*hot_);
  }
  return slot.get();
}

uint32_t WorkbenchWindow::currentSamples() const {
  if (const auto* h = activeHybrid()) return h->framesAccumulated();
  return progressive_->samples();
}

eval::ImageRGBA WorkbenchWindow::currentImage() {
  if (auto* h = activeHybrid()) {
    eval::ImageRGBA img;
    img.width = h->settings().width;
    img.height = h->settings().height;
    img.pixels = h->readOutput();
    for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
    return img;
  }
  eval::ImageRGBA img;
  const auto& tracer = session_->pathTracer();
  img.width = tracer.settings().width;
  img.height = tracer.settings().height;
  img.pixels = tracer.readAccumulation();
  for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
  return img;
}

void WorkbenchWindow::updateLiveError() {
  // Called when no frame is in flight. Only whole samples count: the path tracer's accumulation is read when
  // a sample has just finished (the progressive tracer stops at sample ends when a checkpoint is due).
  auto* h = activeHybrid();
  if (!h && (progressive_->inPreview() || progressive_->cursorRow() != 0)) return;
  if (h && h->framesAccumulated() < hybridFramesSeen_) ++hybridGeneration_;  // reset by a pipeline commit
  if (h) hybridFramesSeen_ = h->framesAccumulated();
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

void WorkbenchWindow::applyState() {
  auto& tracer = session_->pathTracer();
  auto& st = state_;
  bool restart = false;
  if (st.resetCamera) {
    camera_.reset(session_->scene().camera, sceneRadius(session_->scene()));
    cameraChanged_ = true;
    st.resetCamera = false;
  }
  if (cameraChanged_) {
    tracer.setCamera(camera_.state());
    for (auto& h : hybrids_)
      if (h) h->setCamera(camera_.state());
    cameraChanged_ = false;
    restart = true;
  }
  if (st.materialsDirty) {
    session_->gpuScene().updateMaterials(st.materials);
    // Emission or other features the specialised shaders compiled out need the generic build.
    bool emissive = false, specular = false;
    for (const auto& m : st.materials) {
      emissive |= m.emissive != glm::vec3(0.0f);
      specular |= m.specularFactor != 1.0f || m.specularColorFactor != glm::vec3(1.0f);
    }
    const auto& f = tracer.features();
    if (!f.generic && ((emissive && !f.emissive) || (specular && !f.specular))) st.settings.generic = true;
    st.materialsDirty = false;
    restart = true;
  }
  if (st.lightsDirty) {
    session_->gpuScene().updateLights(st.lights);
    for (auto& h : hybrids_)
      if (h) h->setLights(st.lights);
    st.lightsDirty = false;
    restart = true;
  }
  auto& s = st.settings;
  auto& a = applied_.settings;
  const bool envChanged = s.envPath != a.envPath || (s.envPath.empty() && s.envColor != a.envColor);
  if (envChanged) {
    try {
      auto env = std::make_unique<render::GpuEnvironment>(session_->context(), loadEnvironmentData(s));
      tracer.setEnvironment(*env);
      for (auto& h : hybrids_)
        if (h) h->setEnvironment(*env);
      environment_ = std::move(env);  // the previous one is no longer referenced (setEnvironment waited)
      st.envError.clear();
    } catch (const std::exception& e) {
      st.envError = e.what();
      s.envPath = a.envPath;
      s.envColor = a.envColor;
    }
  }
  const bool settingsChanged =
      s.maxBounces != a.maxBounces || s.rrStart != a.rrStart || s.rrMin != a.rrMin || s.rrMax != a.rrMax ||
      s.russianRoulette != a.russianRoulette || s.nee != a.nee || s.mis != a.mis || s.sampler != a.sampler ||
      s.seed != a.seed || s.envIntensity != a.envIntensity || s.envRotationDeg != a.envRotationDeg ||
      s.envColor != a.envColor || s.envPath != a.envPath || s.generic != a.generic || s.defines != a.defines;
  if (settingsChanged) {
    const auto features = featuresFor(session_->scene(), s);
    if (tracer.setFeatures(features)) registerHotReload();
    progressive_->setSettings(s);
    for (auto& h : hybrids_) {
      if (!h) continue;
      render::RenderSettings hs = s;
      hs.width = h->settings().width;
      hs.height = h->settings().height;
      h->setSettings(hs);
    }
    restart = true;
  }
  const auto& hy = st.hybrid;
  const auto& ha = applied_.hybrid;
  if (hy.sunAngleDeg != ha.sunAngleDeg || hy.aoRadius != ha.aoRadius || hy.aoRays != ha.aoRays ||
      hy.temporal != ha.temporal || hy.reflectionDepth != ha.reflectionDepth ||
      hy.reflectionMaxRoughness != ha.reflectionMaxRoughness ||
      hy.reflectionMinMetallic != ha.reflectionMinMetallic) {
    for (auto& h : hybrids_)
      if (h) h->setHybridSettings(hy);
    restart = true;
  }
  if (st.mode != applied_.mode) restart = true;
  if (st.mode != render::RenderMode::PathTrace) ensureHybrid();
  if (st.referencePath != referenceTried_) {
    referenceTried_ = st.referencePath;
    if (st.referencePath.empty()) {
      liveError_.clearReference();
    } else {
      liveError_.loadReference(st.referencePath);  // a failure is shown in the panel (liveError_.error())
    }
  }
  if (st.resetAccumulation) {
    st.resetAccumulation = false;
    restart = true;
  }
  if (st.reloadShaders) {
    hot_->reloadAll();
    st.reloadShaders = false;
  }
  if (st.vsync != applied_.vsync) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    swapchain_->recreate(uint32_t(w), uint32_t(h), st.vsync);
    gui_->swapchainRecreated(*swapchain_);
  }
  auto& opts = progressive_->options();
  opts.targetSpp = st.targetSpp;
  opts.paused = st.paused;
  opts.preview = st.preview;
  opts.budgetMs = st.budgetMs;
  // A rebuild compiling on a CPU device gets most of the cores (render/hot_reload.h).
  if (session_->context().cpuDevice() && hot_ && hot_->compiling())
    opts.budgetMs = st.budgetMs * render::kCpuRenderShareWhileCompiling;
  if (restart) {
    progressive_->invalidate();
    if (auto* h = activeHybrid()) {
      h->resetAccumulation();
      ++hybridResets_;
    }
    ++hybridGeneration_;
    hybridReset_ = Clock::now();
  }
  applied_ = st;
}

void WorkbenchWindow::handleInput(const Rect& view, float dt) {
  ImGuiIO& io = ImGui::GetIO();
  double mx = 0, my = 0;
  glfwGetCursorPos(window_, &mx, &my);
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  const glm::vec2 mouse(float(mx) * float(fw) / float(std::max(ww, 1)),
                        float(my) * float(fh) / float(std::max(wh, 1)));
  const glm::vec2 delta = lastMouse_.x < 0 ? glm::vec2(0.0f) : mouse - lastMouse_;
  const bool overView = view.contains(mouse.x, mouse.y) && !io.WantCaptureMouse;
  const bool left = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool right = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  const bool middle = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                     glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;

  CameraInput in;
  in.dt = dt;
  in.fast = shift;
  if (!dragging_ && overView && (left || right || middle)) {
    dragging_ = true;
    pressMouse_ = mouse;
  }
  if (dragging_) {
    const bool orbit = camera_.mode() == CameraMode::Orbit;
    if ((orbit && left && !shift) || (!orbit && right)) in.dragRotate = delta;
    if ((orbit && (middle || right || (left && shift))) || (!orbit && middle)) in.dragPan = delta;
    if (!left && !right && !middle) {
      dragging_ = false;
      if (glm::length(mouse - pressMouse_) < 3.0f) pickPinned_ = !pickPinned_;  // a click pins the pick
    }
  }
  if (overView) in.wheel = io.MouseWheel;
  if (!io.WantCaptureKeyboard && camera_.mode() == CameraMode::Fly) {
    auto key = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    in.move = {key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
               key(GLFW_KEY_W) - key(GLFW_KEY_S)};
  }
  if (camera_.update(in)) cameraChanged_ = true;

  // Pixel picker: the CPU ray through the pixel under the cursor.
  const Rect img = imageRect(view);
  if (overView && img.contains(mouse.x, mouse.y) && !pickPinned_ && (delta != glm::vec2(0.0f) || !pick_)) {
    const float px = (mouse.x - img.x) / img.w * float(progressive_->targetWidth());
    const float py = (mouse.y - img.y) / img.h * float(progressive_->targetHeight());
    glm::vec3 o, d;
    cameraRay(camera_.state(), progressive_->targetWidth(), progressive_->targetHeight(), px, py, o, d);
    pick_ = pickRay(session_->scene(), o, d);
  }
  lastMouse_ = mouse;

  if (!io.WantCaptureKeyboard) {
    const bool f12 = glfwGetKey(window_, GLFW_KEY_F12) == GLFW_PRESS;
    if (f12 && !f12Down_) state_.saveRequest = "";
    f12Down_ = f12;
    const bool f5 = glfwGetKey(window_, GLFW_KEY_F5) == GLFW_PRESS;
    if (f5 && !f5Down_) state_.reloadShaders = true;
    f5Down_ = f5;
    const bool tab = glfwGetKey(window_, GLFW_KEY_TAB) == GLFW_PRESS;
    if (tab && !tabDown_) state_.showPanel = !state_.showPanel;
    tabDown_ = tab;
    if (glfwGetKey(window_, GLFW_KEY_HOME) == GLFW_PRESS) state_.resetCamera = true;
  }
}

nlohmann::json WorkbenchWindow::parametersJson() {
  const auto& s = session_->pathTracer().settings();
  const auto cam = camera_.state();
  nlohmann::json j;
  j["scene"] = session_->scene().sourcePath.string();
  j["width"] = s.width;
  j["height"] = s.height;
  j["samples"] = currentSamples();
  j["preview"] = !activeHybrid() && progressive_->inPreview();
  j["mode"] = render::renderModeName(state_.mode);
  if (const auto* h = activeHybrid()) {
    j["width"] = h->settings().width;
    j["height"] = h->settings().height;
    j["hybrid"] = hybridSettingsJson(*h);
  }
  j["max_bounces"] = s.maxBounces;
  j["rr"] = {{"enabled", s.russianRoulette}, {"start", s.rrStart}, {"min", s.rrMin}, {"max", s.rrMax}};
  j["nee"] = s.nee;
  j["mis"] = s.mis;
  j["sampler"] = s.sampler == render::SamplerKind::Pcg ? "pcg" : "sobol";
  j["seed"] = s.seed;
  j["generic_shaders"] = s.generic;
  j["environment"] = {{"path", s.envPath},
                      {"color", {s.envColor.x, s.envColor.y, s.envColor.z}},
                      {"rotation_deg", s.envRotationDeg},
                      {"intensity", s.envIntensity}};
  j["exposure"] = state_.display.exposure;
  j["tonemap"] = eval::tonemapName(state_.display.tonemap);
  j["view"] = viewName(state_.display.view);
  const glm::vec3 eye = camera_.eye(), fwd = camera_.forward();
  j["camera"] = {{"eye", {eye.x, eye.y, eye.z}}, {"forward", {fwd.x, fwd.y, fwd.z}}, {"yfov", cam.yfov}};
  return j;
}

nlohmann::json WorkbenchWindow::statsJson() {
  nlohmann::json j;
  j["frames"] = frameCount_;
  j["samples"] = currentSamples();
  j["preview"] = !activeHybrid() && progressive_->inPreview();
  j["resets"] = progressive_->resets() + hybridResets_;
  j["mode"] = render::renderModeName(state_.mode);
  nlohmann::json le;
  le["reference"] = liveError_.referenceName();
  le["error"] = liveError_.error();
  le["history"] = nlohmann::json::array();
  for (const auto& p : liveError_.history()) {
    le["history"].push_back({{"samples", p.samples},
                             {"seconds", p.seconds},
                             {"rmse", p.rmse},
                             {"rel_mse", p.relMse},
                             {"estimated", p.estimated}});
  }
  j["live_error"] = le;
  j["trace_width"] = session_->pathTracer().settings().width;
  j["trace_height"] = session_->pathTracer().settings().height;
  j["target_width"] = progressive_->targetWidth();
  j["target_height"] = progressive_->targetHeight();
  j["window_width"] = swapchain_->extent().width;
  j["window_height"] = swapchain_->extent().height;
  j["present_mode"] = vk::presentModeName(swapchain_->presentMode());
  j["frame_ms"] = {
      {"last", frames_.last()},           {"mean", frames_.mean()}, {"p50", frames_.percentile(0.5f)},
      {"p95", frames_.percentile(0.95f)}, {"max", frames_.max()},   {"count", frames_.count()}};
  j["trace_budget_ms"] = state_.budgetMs;
  j["trace_gpu_ms_last"] = traceMs_;
  j["display_gpu_ms_last"] = displayMs_;
  j["pixels_per_ms"] = progressive_->pixelsPerMs();
  const double secs = std::max(traceSeconds_, 1e-6);
  j["paths_per_second"] = counters_.pathCount / secs;
  j["rays_per_second"] = counters_.rayCount / secs;
  j["nan_inf_dropped"] = counters_.droppedSamples;
  const std::string err = hot_->currentError();
  j["shader_error"] = err;
  j["banner"] = err.empty() ? "" : "shader error (still rendering with the last good pipeline):\n" + err;
  j["reloads"] = nlohmann::json::array();
  for (const auto& e : hot_->history()) j["reloads"].push_back(reloadEventJson(e));
  j["shader_files"] = nlohmann::json::array();
  for (const auto& [path, f] : session_->library().fileStatuses()) {
    j["shader_files"].push_back({{"path", path.string()}, {"ok", f.ok}, {"programs", f.programs}});
  }
  j["parameters"] = parametersJson();
  j["validation_errors"] = session_->context().validationErrors();
  return j;
}

void WorkbenchWindow::writeStats(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write stats '" + path + "'");
  f << statsJson().dump(2) << "\n";
}

void WorkbenchWindow::saveRender(std::string base) {
  if (base.empty()) {
    std::filesystem::create_directories(projectRoot() / "out");
    base = (projectRoot() / "out" / ("workbench_" + timestampName())).string();
  }
  auto image = currentImage();
  eval::writePng(base + ".png", image, state_.display.exposure, state_.display.tonemap);
  eval::writeExr(base + ".exr", image);
  std::ofstream f(base + ".json");
  f << parametersJson().dump(2) << "\n";
  lastSaved_ = std::filesystem::path(base).filename().string() + ".png/.exr/.json";
  std::printf("workbench: saved %s.png (tonemapped), %s.exr (linear), %s.json\n", base.c_str(), base.c_str(),
              base.c_str());
  std::fflush(stdout);
}

void WorkbenchWindow::readTimestamps() {
  uint64_t ts[3] = {};
  if (vkGetQueryPoolResults(session_->context().device(), queries_, 0, 3, sizeof ts, ts, sizeof(uint64_t),
                            VK_QUERY_RESULT_64_BIT) != VK_SUCCESS) {
    return;
  }
  const double period = session_->context().timestampPeriodNs() * 1e-6;
  traceMs_ = double(ts[1] - ts[0]) * period;
  displayMs_ = double(ts[2] - ts[1]) * period;
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
    const bool run =
        !state_.paused && (state_.targetSpp == 0 || hybrid->framesAccumulated() < state_.targetSpp);
    tracedPixels_ = 0;
    if (run) {
      hybrid->record(cmd);
      hybrid->advanceFrame();
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
  push.exposureScale = std::exp2(state_.display.exposure);
  push.tonemap = uint32_t(state_.display.tonemap);
  push.view = hybrid ? WB_VIEW_BEAUTY : state_.display.view;  // the debug views are the path tracer's AOVs
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

int WorkbenchWindow::run() {
  auto& ctx = session_->context();
  auto last = Clock::now();
  auto frameBegin = last;  // when the work of the frame in flight began (after any rest)
  // While a rebuild compiles on a CPU device, the loop rests after each frame so the compile gets most of the
  // cores (render/hot_reload.h): the panel and the present cost ~20 ms per frame on lavapipe besides the
  // trace budget, and without rests an edit took 2.6-3.0 s to reach the window instead of 1.3-1.6 s.
  const double restRatio = render::rebuildRestRatio(ctx.cpuDevice(), render::kWindowShareWhileCompiling);
  int exitCode = 0;
  while (!glfwWindowShouldClose(window_) && !state_.quit) {
    glfwPollEvents();
    // The previous frame: wait for it, then everything that needs the device idle happens here.
    if (frameInFlight_) {
      WB_VK(vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX));
      frameInFlight_ = false;
      readTimestamps();
      hot_->frameFinished(frameBegin);
      if (restRatio > 0 && hot_->compiling()) {
        const auto end = Clock::now();
        const auto until = end + std::chrono::duration_cast<Clock::duration>((end - frameBegin) * restRatio);
        // Input still wakes the loop's event queue; it is handled with the next frame.
        for (auto t = end; hot_->compiling() && t < until; t = Clock::now())
          glfwWaitEventsTimeout(std::chrono::duration<double>(until - t).count());
      }
      counters_ = session_->pathTracer().readCounters();
      updateLiveError();
      if (!captureTarget_.empty()) {
        capture_->write(captureTarget_);
        std::printf("workbench: window screenshot %s\n", captureTarget_.c_str());
        std::fflush(stdout);
        captureTarget_.clear();
      }
    }
    const auto now = Clock::now();
    const float dt = std::chrono::duration<float>(now - last).count();
    if (frameCount_ > 0) frames_.add(dt * 1000.0f);
    last = now;
    frameBegin = now;

    if (options_.frames && frameCount_ >= options_.frames) break;
    if (hasScript_) {
      try {
        // A finished script still lets a requested screenshot reach the screen.
        if (!script_.step(*this) && !options_.frames && screenshotPath_.empty()) break;
      } catch (const std::exception& e) {
        fatalScriptError_ = e.what();
        exitCode = 1;
        break;
      }
    }
    hot_->poll();

    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window_, &fbw, &fbh);
    if (fbw == 0 || fbh == 0) {  // minimised: nothing to draw into
      glfwWaitEventsTimeout(0.1);
      continue;
    }
    if (uint32_t(fbw) != swapchain_->extent().width || uint32_t(fbh) != swapchain_->extent().height) {
      if (!swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync)) continue;
      gui_->swapchainRecreated(*swapchain_);
    }

    gui_->beginFrame();
    PanelContext pc{
        state_,
        session_->scene(),
        *progressive_,
        *hot_,
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
        &liveError_};
    const float W = float(swapchain_->extent().width), H = float(swapchain_->extent().height);
    panelWidth_ = drawSidePanel(pc, W, H);
    const Rect view{panelWidth_, 0.0f, std::max(W - panelWidth_, 1.0f), H};
    drawOverlays(pc, imageRect(view));
    handleInput(view, dt);

    // The trace resolution follows the view (times the resolution scale) unless --size fixed it.
    if (state_.fixedSize) {
      progressive_->setTargetSize(uint32_t(std::lround(state_.fixedWidth * state_.resolutionScale)),
                                  uint32_t(std::lround(state_.fixedHeight * state_.resolutionScale)));
    } else {
      progressive_->setTargetSize(uint32_t(std::lround(view.w * state_.resolutionScale)),
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
      render::RenderSettings hs = state_.settings;
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
                          tracer.aovImage(render::Aov::Info).view(), progressive_->previewImage().view()});

    auto index = swapchain_->acquire(imageAvailable_);
    if (!index) {
      ImGui::EndFrame();
      swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync);
      gui_->swapchainRecreated(*swapchain_);
      continue;
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
    if (!swapchain_->present(*index, done)) {
      glfwGetFramebufferSize(window_, &fbw, &fbh);
      vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
      swapchain_->recreate(uint32_t(fbw), uint32_t(fbh), state_.vsync);
      gui_->swapchainRecreated(*swapchain_);
    }
    ++frameCount_;
  }
  if (frameInFlight_) {
    vkWaitForFences(ctx.device(), 1, &fence_, VK_TRUE, UINT64_MAX);
    readTimestamps();
    counters_ = session_->pathTracer().readCounters();
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

bool parseWindowSize(const std::string& text, uint32_t& w, uint32_t& h) {
  unsigned a = 0, b = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%u%c%u", &a, &x, &b) != 3 || (x != 'x' && x != 'X') || a < 64 || b < 64)
    return false;
  w = a;
  h = b;
  return true;
}

}  // namespace

std::vector<std::string> renderArgsOnly(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (size_t i = 0; i < args.size(); ++i) {
    const auto& a = args[i];
    bool skip = false;
    for (const auto& f : kWindowValueFlags) {
      if (a == f) {
        skip = true;
        ++i;  // its value too
      } else if (a.rfind(f + "=", 0) == 0) {
        skip = true;
      }
    }
    for (const auto& f : kWindowBoolFlags) skip = skip || a == f;
    if (!skip) out.push_back(a);
  }
  return out;
}

int runWindowCommand(const std::vector<std::string>& args) {
  CLI::App cli(
      "The live workbench: progressive path tracing in a window with inspection panels and shader hot "
      "reload",
      "workbench");
  WindowOptions o;
  addRenderOptions(cli, o.render);
  cli.add_option("--window", o.windowSize, "window size WxH")->capture_default_str();
  cli.add_option("--scale", o.scale, "trace resolution relative to the view (0.1..2)")->capture_default_str();
  cli.add_option("--frames", o.frames, "render N frames, then exit (with --screenshot: save the last one)");
  cli.add_option("--screenshot", o.screenshot, "PNG of the window (panel included) at exit");
  cli.add_option("--stats", o.statsPath,
                 "JSON statistics at exit (samples, resets, frame times, shader errors)");
  cli.add_option("--reference", o.reference,
                 "converged .exr of the same view: the Stats panel shows the running error against it");
  cli.add_option("--script", o.scriptPath, "run scripted commands (see src/app/window/script.h)");
  cli.add_option("--set", o.sets, std::string("NAME=VALUE setting at start; names: ") + settingNamesHelp());
  cli.add_option("--imgui-ini", o.imguiIni, "read and write the panel layout in this file (default: none)");
  cli.add_flag("--no-vsync", o.noVsync, "present with MAILBOX/IMMEDIATE instead of FIFO");
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    cli.parse(reversed);
    o.sizeGiven = cli.get_option("--size")->count() > 0;
    finishRenderOptions(o.render);
    if (!parseWindowSize(o.windowSize, o.windowWidth, o.windowHeight))
      throw std::invalid_argument("--window: expected WxH (at least 64x64), got '" + o.windowSize + "'");
    if (!(o.scale > 0.0f && o.scale <= 2.0f)) throw std::invalid_argument("--scale: expected 0 < scale <= 2");
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", cli.help().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench: error: %s\n", e.what());
    return 2;
  }

  if (!glfwInit()) return kNoDisplay;
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    return kNoDisplay;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  GLFWwindow* window =
      glfwCreateWindow(int(o.windowWidth), int(o.windowHeight), "workbench", nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    return kNoDisplay;
  }
  int code = 0;
  try {
    WorkbenchWindow app(window, o);
    code = app.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench: error: %s\n", e.what());
    code = 1;
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace wb::app
