#include "app/window/window_input.h"

#include <algorithm>

#include <GLFW/glfw3.h>
#include <imgui.h>

namespace wb::app {

float sceneRadius(const scene::Scene& s) {
  return std::max(0.5f * glm::length(s.bounds.max - s.bounds.min), 1e-3f);
}

WindowInput::WindowInput(GLFWwindow* window, InputEvents& events, live::LiveSession& session)
    : window_(window), events_(events), session_(session) {
  camera_.reset(session.render().scene().camera, sceneRadius(session.render().scene()));
}

void WindowInput::cameraMoved() {
  session_.setCamera(camera_.state());
}

void WindowInput::resetCamera() {
  camera_.reset(session_.render().scene().camera, sceneRadius(session_.render().scene()));
  cameraMoved();
}

void WindowInput::orbit(float dx, float dy) {
  CameraInput in;
  in.dragRotate = {dx, dy};
  if (camera_.update(in)) cameraMoved();
}

void WindowInput::handle(const Rect& view, const Rect& img, float dt) {
  auto& state = session_.state();
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
  for (const ButtonChange& b : events_.takeButtonChanges()) {
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
  if (clicked) {
    pickPinned_ = !pickPinned_;  // a click pins the pick
    if (img.contains(pressMouse_.x, pressMouse_.y))
      session_.inspectAt((pressMouse_ - glm::vec2(img.x, img.y)) / glm::vec2(img.w, img.h));
  }
  if (overView) in.wheel = io.MouseWheel;
  if (!io.WantCaptureKeyboard && camera_.mode() == CameraMode::Fly) {
    auto key = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    in.move = {key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
               key(GLFW_KEY_W) - key(GLFW_KEY_S)};
  }
  if (camera_.update(in)) cameraMoved();

  // Pixel picker: the CPU ray through the pixel under the cursor.
  const uint32_t tw = session_.traceWidth(), th = session_.traceHeight();
  if (overView && img.contains(mouse.x, mouse.y) && !pickPinned_ && (delta != glm::vec2(0.0f) || !pick_)) {
    const float px = (mouse.x - img.x) / img.w * float(tw);
    const float py = (mouse.y - img.y) / img.h * float(th);
    glm::vec3 o, d;
    cameraRay(camera_.state(), tw, th, px, py, o, d);
    pick_ = pickRay(session_.render().scene(), o, d);
  }
  lastMouse_ = mouse;

  // Keys from the event queue: every press counts, however short and however slow the frame.
  for (const KeyPress& k : events_.takeKeyPresses()) {
    if (io.WantCaptureKeyboard) continue;
    ++keyPresses_;
    switch (k.key) {
      case GLFW_KEY_F12:
        state.saveRequest = "";
        break;
      case GLFW_KEY_F5:
        state.reloadShaders = true;
        break;
      case GLFW_KEY_TAB:
        state.showPanel = !state.showPanel;
        break;
      case GLFW_KEY_HOME:
        state.resetCamera = true;
        break;
      default:
        break;
    }
  }
}

}  // namespace wb::app
