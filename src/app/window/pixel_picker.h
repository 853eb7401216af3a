// The Inspect panel's pixel picker: casts the camera ray through a pixel against the scene's triangles on the
// CPU (brute force, Möller-Trumbore) and reports what it hit.
#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "render/path_tracer.h"
#include "scene/scene.h"

namespace wb::app {

struct PickResult {
  int instance = -1, mesh = -1, primitive = -1, triangle = -1, material = -1;
  std::string nodeName, meshName, materialName;
  glm::vec3 position{0.0f};
  float distance = 0.0f;
  glm::vec3 shadingNormal{0.0f}, geometricNormal{0.0f};
  glm::vec2 uv{0.0f};
  glm::vec3 barycentrics{0.0f};
};

// The world-space ray through pixel (px, py) (pixel centres at +0.5) of a width x height image, as the raygen
// shader builds it (without jitter).
void cameraRay(const render::CameraState& camera, uint32_t width, uint32_t height, float px, float py,
               glm::vec3& origin, glm::vec3& direction);

std::optional<PickResult> pickRay(const scene::Scene& scene, const glm::vec3& origin,
                                  const glm::vec3& direction);

}  // namespace wb::app
