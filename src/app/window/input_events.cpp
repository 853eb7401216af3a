#include "app/window/input_events.h"

#include <chrono>

#include <utility>

#include <GLFW/glfw3.h>

namespace wb::app {
namespace {

InputEvents* eventsOf(GLFWwindow* w) {
  return static_cast<InputEvents*>(glfwGetWindowUserPointer(w));
}

}  // namespace

InputEvents::InputEvents(GLFWwindow* window) : window_(window) {
  glfwSetWindowUserPointer(window, this);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    if (auto* e = eventsOf(w)) e->onKey(key, action, mods);
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int action, int) {
    if (auto* e = eventsOf(w)) e->onButton(button, action);
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double) {
    if (auto* e = eventsOf(w)) e->onActivity(true);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    if (auto* e = eventsOf(w)) e->onCursor(x, y);
  });
}

InputEvents::~InputEvents() {
  glfwSetWindowUserPointer(window_, nullptr);
}

void InputEvents::onKey(int key, int action, int mods) {
  std::lock_guard lock(mutex_);
  activity_ = discrete_ = true;
  if (action == GLFW_PRESS) keys_.push_back({key, mods});
}

void InputEvents::onCursor(double x, double y) {
  {
    std::lock_guard lock(mutex_);
    cursor_ = glm::dvec2(x, y);
  }
  onActivity();
}

void InputEvents::onButton(int button, int action) {
  // Where the button changed: the last motion event's position, in the order the events came. (X11's
  // glfwGetCursorPos asks the server where the pointer is now, which can be several motions further on
  // when the loop polls late: a drag would lose its start.)
  double x = 0, y = 0;
  std::optional<glm::dvec2> cursor;
  {
    std::lock_guard lock(mutex_);
    cursor = cursor_;
  }
  if (cursor) {
    x = cursor->x;
    y = cursor->y;
  } else {
    glfwGetCursorPos(window_, &x, &y);
  }
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(window_, &ww, &wh);
  glfwGetFramebufferSize(window_, &fw, &fh);
  const glm::vec2 pos(float(x) * float(fw) / float(ww > 0 ? ww : 1),
                      float(y) * float(fh) / float(wh > 0 ? wh : 1));
  std::lock_guard lock(mutex_);
  activity_ = discrete_ = true;
  buttons_.push_back({button, action == GLFW_PRESS, pos});
  if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_RELEASE)
    releaseNs_.push_back(std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::steady_clock::now().time_since_epoch())
                             .count());
}

std::vector<int64_t> InputEvents::leftReleaseTimes() const {
  std::lock_guard lock(mutex_);
  return releaseNs_;
}

void InputEvents::onActivity(bool discrete) {
  std::lock_guard lock(mutex_);
  activity_ = true;
  discrete_ = discrete_ || discrete;
}

std::vector<KeyPress> InputEvents::takeKeyPresses() {
  std::lock_guard lock(mutex_);
  return std::exchange(keys_, {});
}

std::vector<ButtonChange> InputEvents::takeButtonChanges() {
  std::lock_guard lock(mutex_);
  return std::exchange(buttons_, {});
}

bool InputEvents::takeActivity() {
  std::lock_guard lock(mutex_);
  return std::exchange(activity_, false);
}

bool InputEvents::takeDiscrete() {
  std::lock_guard lock(mutex_);
  return std::exchange(discrete_, false);
}

}  // namespace wb::app
