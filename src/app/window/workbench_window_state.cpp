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
    session_->setCamera(camera_.state());
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
    if (!f.generic && ((emissive && !f.emissive) || (specular && !f.specular)))
      st.params.render.generic = true;
    st.materialsDirty = false;
    restart = true;
  }
  if (st.lightsDirty) {
    session_->setLights(st.lights);
    st.lightsDirty = false;
    restart = true;
  }
  auto& s = st.params.render;
  auto& a = applied_.params.render;
  const bool envChanged = s.envPath != a.envPath || (s.envPath.empty() && s.envColor != a.envColor);
  if (envChanged) {
    try {
      session_->setEnvironment(s);
      st.envError.clear();
    } catch (const std::exception& e) {
      st.envError = e.what();
      s.envPath = a.envPath;
      s.envColor = a.envColor;
    }
  }
  // The parameters that restart accumulation (render/parameters.h), by what they belong to.
  bool settingsChanged = false, hybridChanged = false;
  for (const auto* p : render::changedParameters(st.params, applied_.params)) {
    if (p->group == "Hybrid") {
      hybridChanged = true;
    } else if (p->name != "mode") {
      settingsChanged = true;
    }
  }
  if (settingsChanged) {
    const auto features = render::featuresFor(session_->scene(), s);
    tracer.setFeatures(features);
    progressive_->setSettings(s);
    for (auto mode : {render::RenderMode::Hybrid, render::RenderMode::Reflections}) {
      auto* h = session_->rendererFor(mode);
      if (!h) continue;
      render::RenderSettings hs = s;
      hs.width = h->settings().width;
      hs.height = h->settings().height;
      h->setSettings(hs);
    }
    restart = true;
  }
  if (hybridChanged) {
    session_->setHybridSettings(st.params.hybrid);
    restart = true;
  }
  if (st.params.mode != applied_.params.mode) restart = true;
  applyMode();
  if (applyInspection()) restart = true;
  if (st.referencePath != referenceTried_) {
    referenceTried_ = st.referencePath;
    if (st.referencePath.empty()) {
      liveError_.clearReference();
    } else {
      // A failure is shown in the panel (liveError_.error()) and said on the terminal, where --reference was
      // typed.
      if (!liveError_.loadReference(st.referencePath))
        std::fprintf(stderr, "workbench: reference %s not used: %s (the running error is a noise estimate)\n",
                     st.referencePath.c_str(), liveError_.error().c_str());
    }
  }
  if (st.resetAccumulation) {
    st.resetAccumulation = false;
    restart = true;
  }
  if (st.reloadShaders) {
    loop_->hot().reloadAll();
    st.reloadShaders = false;
  }
  if (st.vsync != applied_.vsync) {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    swapchain_->recreate(uint32_t(w), uint32_t(h), st.vsync);
    gui_->swapchainRecreated(*swapchain_);
  }
  auto& opts = progressive_->options();
  opts.targetSpp = st.params.render.spp;
  opts.paused = st.paused;
  opts.preview = st.preview;
  opts.budgetMs = st.budgetMs;
  // A rebuild compiling gets the share of the cores the device's policy gives it.
  if (loop_ && loop_->compiling())
    opts.budgetMs = st.budgetMs * session_->context().policy().windowTraceShareWhileCompiling;
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
  const bool shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                     glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;

  // Buttons from the event queue: a drag starts where its button went down (its first motion is measured
  // from there), and a click shorter than a frame still counts.
  const bool overPanel = io.WantCaptureMouse;
  bool clicked = false;
  for (const ButtonChange& b : input_->takeButtonChanges()) {
    if (b.pressed) {
      if (!dragging_ && view.contains(b.position.x, b.position.y) && !overPanel) {
        dragging_ = true;
        dragButton_ = b.button;
        pressMouse_ = lastMouse_ = b.position;
      }
    } else if (dragging_ && b.button == dragButton_) {
      dragging_ = false;
      if (glm::length(b.position - pressMouse_) < 3.0f) clicked = true;
    }
  }
  const glm::vec2 delta = lastMouse_.x < 0 ? glm::vec2(0.0f) : mouse - lastMouse_;
  const bool overView = view.contains(mouse.x, mouse.y) && !overPanel;

  CameraInput in;
  in.dt = dt;
  in.fast = shift;
  if (dragging_) {
    const bool orbit = camera_.mode() == CameraMode::Orbit;
    const bool left = dragButton_ == GLFW_MOUSE_BUTTON_LEFT, right = dragButton_ == GLFW_MOUSE_BUTTON_RIGHT;
    const bool middle = dragButton_ == GLFW_MOUSE_BUTTON_MIDDLE;
    if ((orbit && left && !shift) || (!orbit && right)) in.dragRotate = delta;
    if ((orbit && (middle || right || (left && shift))) || (!orbit && middle)) in.dragPan = delta;
  }
  if (clicked) pickPinned_ = !pickPinned_;  // a click pins the pick
  if (clicked) inspectClick(imageRect(view), pressMouse_);
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

  // Keys from the event queue: every press counts, however short and however slow the frame.
  for (const KeyPress& k : input_->takeKeyPresses()) {
    if (io.WantCaptureKeyboard) continue;
    ++keyPressesHandled_;
    switch (k.key) {
      case GLFW_KEY_F12:
        state_.saveRequest = "";
        break;
      case GLFW_KEY_F5:
        state_.reloadShaders = true;
        break;
      case GLFW_KEY_TAB:
        state_.showPanel = !state_.showPanel;
        break;
      case GLFW_KEY_HOME:
        state_.resetCamera = true;
        break;
      default:
        break;
    }
  }
}

}  // namespace wb::app
