// Interactive camera: orbit (drag to rotate about a target, wheel to dolly, shift-drag or middle-drag to pan)
// and fly (right-drag to look, WASD + QE to move). Reset returns to the scene's camera. Drags are scaled to
// the view: a drag across the view's width turns the camera by 180 degrees, and a pan moves the scene with
// the cursor at the target's depth.
#pragma once
#include <glm/glm.hpp>

#include "render/path_tracer.h"
#include "scene/scene.h"

namespace wb::app {

enum class CameraMode { Orbit, Fly };

struct CameraInput {
  glm::vec2 dragRotate{0.0f};   // pixels of rotate drag this frame
  glm::vec2 dragPan{0.0f};      // pixels of pan drag this frame
  float wheel = 0.0f;           // scroll steps
  glm::vec3 move{0.0f};         // fly: x right, y up, z forward, each -1..1
  float dt = 0.0f;              // seconds since the last frame
  bool fast = false;            // shift held
  glm::vec2 viewSize{1000.0f};  // the image's size on screen in pixels (the drags' scale)
};

class CameraController {
 public:
  void reset(const scene::Camera& camera, float sceneRadius);
  // Applies input; returns true when the camera moved (the accumulation must restart).
  bool update(const CameraInput& input);
  void setMode(CameraMode mode);
  CameraMode mode() const { return mode_; }

  render::CameraState state() const;
  glm::vec3 eye() const { return eye_; }
  glm::vec3 forward() const;
  float yfov() const { return yfov_; }
  float speed = 1.0f;  // fly speed in scene radii per second

 private:
  CameraMode mode_ = CameraMode::Orbit;
  glm::vec3 eye_{0.0f, 0.0f, 1.0f};
  glm::vec3 target_{0.0f};
  float yaw_ = 0.0f, pitch_ = 0.0f;  // radians; yaw 0 looks along -Z
  float distance_ = 1.0f;
  float yfov_ = 0.7f, znear_ = 0.01f;
  float radius_ = 1.0f;
};

}  // namespace wb::app
