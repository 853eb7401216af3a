#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace wb::scene {

Camera frameBounds(const Bounds& bounds, float yfov) {
  const glm::vec3 center = 0.5f * (bounds.min + bounds.max);
  float radius = 0.5f * glm::length(bounds.max - bounds.min);
  if (!(radius > 1e-6f) || !std::isfinite(radius)) radius = 1.0f;
  const float fov = (yfov > 0.01f && yfov < 3.1f) ? yfov : 0.7f;
  // Distance at which the bounding sphere fits the vertical field of view, plus a small margin.
  const float distance = 1.1f * radius / std::sin(0.5f * fov);
  Camera camera;
  camera.target = center;
  camera.eye = center + glm::vec3(0.0f, 0.0f, distance);
  camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.yfov = fov;
  camera.aspect = 0.0f;
  camera.znear = std::max(1e-4f, 0.01f * distance);
  camera.zfar = distance + 10.0f * radius;
  camera.fromFile = false;
  return camera;
}

}  // namespace wb::scene
