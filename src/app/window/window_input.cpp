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
  in.viewSize = viewSize_;
  if (camera_.update(in)) cameraMoved();
}

std::optional<PickResult> WindowInput::pickAt(const Rect& img, glm::vec2 mouse) const {
  if (!img.contains(mouse.x, mouse.y)) return std::nullopt;
  const uint32_t tw = session_.traceWidth(), th = session_.traceHeight();
  const float px = (mouse.x - img.x) / img.w * float(tw);
  const float py = (mouse.y - img.y) / img.h * float(th);
  glm::vec3 o, d;
  cameraRay(camera_.state(), tw, th, px, py, o, d);
  return pickRay(session_.render().scene(), o, d);
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
  // A drag that ended this frame still moves the camera up to where its button went up.
  std::optional<int> endedDrag;
  glm::vec2 dragEnd(0.0f);
  for (const ButtonChange& b : events_.takeButtonChanges()) {
    if (b.pressed) {
      if (!dragging_ && view.contains(b.position.x, b.position.y) && !overPanel) {
        dragging_ = true;
        dragButton_ = b.button;
        pressMouse_ = lastMouse_ = b.position;
      }
    } else if (dragging_ && b.button == dragButton_) {
      dragging_ = false;
      endedDrag = b.button;
      dragEnd = b.position;
      if (glm::length(b.position - pressMouse_) < 3.0f && b.button == GLFW_MOUSE_BUTTON_LEFT) clicked = true;
    }
  }
  const glm::vec2 delta = lastMouse_.x < 0 ? glm::vec2(0.0f) : (endedDrag ? dragEnd : mouse) - lastMouse_;
  const bool overView = view.contains(mouse.x, mouse.y) && !overPanel;

  CameraInput in;
  in.dt = dt;
  in.fast = shift;
  in.viewSize = viewSize_ = glm::vec2(img.w, img.h);
  if (dragging_ || endedDrag) {
    const int button = endedDrag ? *endedDrag : dragButton_;
    const bool orbit = camera_.mode() == CameraMode::Orbit;
    const bool left = button == GLFW_MOUSE_BUTTON_LEFT, right = button == GLFW_MOUSE_BUTTON_RIGHT;
    const bool middle = button == GLFW_MOUSE_BUTTON_MIDDLE;
    if ((orbit && left && !shift) || (!orbit && right)) in.dragRotate = delta;
    if ((orbit && (middle || right || (left && shift))) || (!orbit && middle)) in.dragPan = delta;
  }
  if (clicked && img.contains(pressMouse_.x, pressMouse_.y)) {
    // A click selects the object under it for the material editor (none: the selection is cleared) and picks
    // the inspected pixel.
    selected_ = pickAt(img, pressMouse_);
    session_.inspectAt((pressMouse_ - glm::vec2(img.x, img.y)) / glm::vec2(img.w, img.h));
  }
  if (overView) in.wheel = io.MouseWheel;
  if (!io.WantCaptureKeyboard && camera_.mode() == CameraMode::Fly) {
    auto key = [&](int k) { return glfwGetKey(window_, k) == GLFW_PRESS ? 1.0f : 0.0f; };
    in.move = {key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q),
               key(GLFW_KEY_W) - key(GLFW_KEY_S)};
  }
  const bool moved = camera_.update(in);
  if (moved) cameraMoved();

  // Hover: the CPU ray through the pixel under the cursor names what is there (it selects nothing).
  if (!overView || !img.contains(mouse.x, mouse.y)) {
    hover_.reset();
  } else if (mouse != hoverAt_ || !hover_ || moved) {
    // The cursor moved since the last pick (a press resets the drag's origin, not this), or the camera did.
    hover_ = pickAt(img, mouse);
    hoverAt_ = mouse;
  }
  lastMouse_ = mouse;

  // Keys from the event queue: every press counts, however short and however slow the frame.
  for (const KeyPress& k : events_.takeKeyPresses()) {
    // Ctrl+Q quits whatever has the keyboard; Esc closes an open popup first (ImGui does), else quits.
    if (k.key == GLFW_KEY_Q && (k.mods & GLFW_MOD_CONTROL)) {
      ++keyPresses_;
      state.quit = true;
      continue;
    }
    if (io.WantCaptureKeyboard) continue;
    if (k.key == GLFW_KEY_ESCAPE && ImGui::IsPopupOpen(nullptr, ImGuiPopupFlags_AnyPopupId)) continue;
    ++keyPresses_;
    switch (k.key) {
      case GLFW_KEY_ESCAPE:
        state.quit = true;
        break;
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
