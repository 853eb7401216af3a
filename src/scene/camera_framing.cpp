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
  // Looking down -Z, unless the model is (nearly) flat seen that way: a ground plane in XZ or a wall in YZ
  // would show as a line. Then the camera looks along the axis of the model's smallest extent, at the face
  // with the largest projected area. Models with some depth keep the -Z view.
  const glm::vec3 extent = glm::max(bounds.max - bounds.min, glm::vec3(0.0f));
  const float areaZ = extent.x * extent.y, areaY = extent.x * extent.z, areaX = extent.y * extent.z;
  const float largest = std::max({areaX, areaY, areaZ});
  glm::vec3 direction(0.0f, 0.0f, 1.0f), up(0.0f, 1.0f, 0.0f);
  if (std::isfinite(largest) && largest > 0.0f && areaZ < 0.05f * largest) {
    if (areaY >= areaX) {
      direction = glm::vec3(0.0f, 1.0f, 0.0f);  // from above, -Z at the top of the image
      up = glm::vec3(0.0f, 0.0f, -1.0f);
    } else {
      direction = glm::vec3(1.0f, 0.0f, 0.0f);  // from +X, Y up
    }
  }
  Camera camera;
  camera.target = center;
  camera.eye = center + direction * distance;
  camera.up = up;
  camera.yfov = fov;
  camera.aspect = 0.0f;
  camera.znear = std::max(1e-4f, 0.01f * distance);
  camera.zfar = distance + 10.0f * radius;
  camera.fromFile = false;
  return camera;
}

}  // namespace wb::scene
