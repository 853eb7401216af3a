// The workbench window: what the panel and scripts changed, applied to the renderers at a frame boundary;
// mouse and keyboard input.
#include "app/window/workbench_window.h"

#include <cstdio>

#include <imgui.h>

#include "app/render_options.h"

namespace wb::app {

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
      const auto data = loadEnvironmentData(s);
      for (const auto& w : data.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
      auto env = std::make_unique<render::GpuEnvironment>(session_->context(), data);
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

}  // namespace wb::app
