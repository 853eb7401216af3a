// Key presses and mouse button changes as GLFW reports them through its callbacks, queued until the frame
// loop takes them: at a few frames a second a quick tap happens between two frames, and polling the key state
// would miss it. Every press is kept, with the cursor position of a button change (a drag starts where the
// button went down, not where the cursor is when the next frame looks).
#pragma once
#include <cstdint>
#include <mutex>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace wb::app {

struct KeyPress {
  int key = 0;
  int mods = 0;
};

struct ButtonChange {
  int button = 0;
  bool pressed = false;
  glm::vec2 position{0.0f};  // framebuffer pixels
};

class InputEvents {
 public:
  // Installs the callbacks on `window` (before ImGui's backend installs its own, which then chain to these).
  explicit InputEvents(GLFWwindow* window);
  ~InputEvents();
  InputEvents(const InputEvents&) = delete;
  InputEvents& operator=(const InputEvents&) = delete;

  // The events since the last call, in order.
  std::vector<KeyPress> takeKeyPresses();
  std::vector<ButtonChange> takeButtonChanges();
  // Whether any input (key, button, scroll, cursor motion) arrived since the last call.
  bool takeActivity();
  // Whether a discrete input (key, button, scroll: not cursor motion) arrived since the last call: the window
  // redraws at once, without waiting for a trace.
  bool takeDiscrete();

  // When the window's event loop received each left button release (steady clock, ns since its epoch): a
  // click's wait for the loop to poll, against the time it takes to reach the screen.
  std::vector<int64_t> leftReleaseTimes() const;

  // The callbacks' entry points (public for the C callbacks).
  void onKey(int key, int action, int mods);
  void onButton(int button, int action);
  void onCursor(double x, double y);  // window coordinates, as GLFW reports a motion
  void onActivity(bool discrete = false);

 private:
  GLFWwindow* window_;
  mutable std::mutex mutex_;
  std::vector<KeyPress> keys_;
  std::vector<ButtonChange> buttons_;
  std::vector<int64_t> releaseNs_;
  std::optional<glm::dvec2> cursor_;  // the last motion event's position (window coordinates)
  bool activity_ = false;
  bool discrete_ = false;
};

}  // namespace wb::app
