// The window's mouse and keyboard: drags move the camera (orbit, pan, fly; scaled to the view), the wheel
// dollies, a click on the image selects the object under it (the material editor edits it) and picks the
// inspected pixel, hovering names what is under the cursor (a CPU ray against the scene), and the window's
// keys (F5 reload, F12 save, Tab panels, Home camera, Esc or Ctrl+Q quit) become session requests. Events
// come from the queue InputEvents keeps, so no press is lost however slow the frame.
#pragma once
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "app/window/camera_controller.h"
#include "app/window/input_events.h"
#include "app/window/panels.h"
#include "app/window/pixel_picker.h"
#include "live/live_session.h"

struct GLFWwindow;

namespace wb::app {

class WindowInput {
 public:
  WindowInput(GLFWwindow* window, InputEvents& events, live::LiveSession& session);

  // Once per drawn frame, after the panels (ImGui knows what the mouse is over): `view` is the area beside
  // the panel, `image` the trace image's rectangle in it.
  void handle(const Rect& view, const Rect& image, float dt);
  // The script's `orbit`: a drag of the orbit camera by (dx, dy) pixels.
  void orbit(float dx, float dy);
  // Home / reset_camera: back to the scene's camera.
  void resetCamera();

  CameraController& camera() { return camera_; }
  // What is under the cursor (hover), and the object the last click on the image selected.
  const std::optional<PickResult>& hover() const { return hover_; }
  const std::optional<PickResult>& selected() const { return selected_; }
  bool dragging() const { return dragging_; }
  uint64_t keyPresses() const { return keyPresses_; }

 private:
  void cameraMoved();

  GLFWwindow* window_;
  InputEvents& events_;
  live::LiveSession& session_;
  // The object under `mouse` (framebuffer pixels) in the image rectangle, if any.
  std::optional<PickResult> pickAt(const Rect& image, glm::vec2 mouse) const;

  CameraController camera_;
  std::optional<PickResult> hover_, selected_;
  glm::vec2 viewSize_{1000.0f};  // the image's size on screen at the last frame (the script's orbit uses it)
  glm::vec2 lastMouse_{-1.0f};
  glm::vec2 hoverAt_{-1.0f};  // where the cursor was when hover_ was picked
  glm::vec2 pressMouse_{0.0f};
  bool dragging_ = false;
  int dragButton_ = -1;
  uint64_t keyPresses_ = 0;
};

// Half the diagonal of the scene's bounds (at least 1e-3): the orbit camera's radius, the depth view's scale.
float sceneRadius(const scene::Scene& s);

}  // namespace wb::app
