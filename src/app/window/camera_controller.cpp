#include "app/window/camera_controller.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace wb::app {
namespace {

// A drag across the whole view turns by this much.
constexpr float kRadiansPerViewWidth = 3.14159265f;
constexpr float kMaxPitch = 1.55f;

glm::vec3 directionFrom(float yaw, float pitch) {
  return {std::cos(pitch) * std::sin(yaw) * -1.0f, std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

}  // namespace

void CameraController::reset(const scene::Camera& camera, float sceneRadius) {
  eye_ = camera.eye;
  target_ = camera.target;
  yfov_ = camera.yfov;
  znear_ = camera.znear > 0.0f ? camera.znear : 0.01f;
  radius_ = std::max(sceneRadius, 1e-3f);
  glm::vec3 d = target_ - eye_;
  distance_ = std::max(glm::length(d), 1e-3f);
  d /= distance_;
  pitch_ = std::asin(std::clamp(d.y, -1.0f, 1.0f));
  yaw_ = std::atan2(-d.x, -d.z);
}

void CameraController::setMode(CameraMode mode) {
  if (mode == mode_) return;
  mode_ = mode;
  // Orbit about the point in front of the camera at the current distance.
  if (mode_ == CameraMode::Orbit) target_ = eye_ + forward() * distance_;
}

glm::vec3 CameraController::forward() const {
  return directionFrom(yaw_, pitch_);
}

bool CameraController::update(const CameraInput& in) {
  bool changed = false;
  const glm::vec2 view = glm::max(in.viewSize, glm::vec2(16.0f));
  if (in.dragRotate != glm::vec2(0.0f)) {
    // Orbit: dragging right moves the camera right around the target; fly: looks right.
    const float sign = mode_ == CameraMode::Orbit ? 1.0f : -1.0f;
    const float radiansPerPixel = kRadiansPerViewWidth / view.x;
    yaw_ += sign * in.dragRotate.x * radiansPerPixel;
    pitch_ = std::clamp(pitch_ + sign * in.dragRotate.y * radiansPerPixel, -kMaxPitch, kMaxPitch);
    changed = true;
  }
  const glm::vec3 fwd = forward();
  const glm::vec3 right = glm::normalize(glm::cross(fwd, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(right, fwd);
  if (in.dragPan != glm::vec2(0.0f)) {
    // The view's height spans 2 d tan(fov / 2) at the target's depth d: the scene there follows the cursor.
    const float scale = distance_ * 2.0f * std::tan(yfov_ * 0.5f) / view.y;
    const glm::vec3 delta = (-in.dragPan.x * right + in.dragPan.y * up) * scale;
    target_ += delta;
    eye_ += delta;
    changed = true;
  }
  if (mode_ == CameraMode::Orbit) {
    if (in.wheel != 0.0f) {
      distance_ = std::max(distance_ * std::pow(0.85f, in.wheel), radius_ * 1e-3f);
      changed = true;
    }
    eye_ = target_ - fwd * distance_;
  } else {
    glm::vec3 move = in.move;
    if (in.wheel != 0.0f) move.z += in.wheel * 5.0f;  // a scroll step nudges forward
    if (move != glm::vec3(0.0f)) {
      const float step = speed * radius_ * in.dt * (in.fast ? 4.0f : 1.0f);
      eye_ += (move.x * right + move.y * up + move.z * fwd) * step;
      changed = true;
    }
    target_ = eye_ + fwd * distance_;
  }
  return changed;
}

render::CameraState CameraController::state() const {
  render::CameraState c;
  c.view = glm::lookAt(eye_, eye_ + forward(), glm::vec3(0.0f, 1.0f, 0.0f));
  c.yfov = yfov_;
  c.znear = znear_;
  return c;
}

}  // namespace wb::app
