#include "scene/scene.h"

#include <cmath>

namespace wb::scene {

size_t Scene::triangleCount() const {
  size_t count = 0;
  for (const Instance& instance : instances) {
    if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= meshes.size()) continue;
    for (const Primitive& primitive : meshes[static_cast<size_t>(instance.mesh)].primitives) {
      count += primitive.indices.size() / 3;
    }
  }
  return count;
}

float sunCosAngularRadius(float lightCosAngularRadius, float sunAngleDeg) {
  return sunAngleDeg >= 0.0f ? std::cos(glm::radians(sunAngleDeg * 0.5f)) : lightCosAngularRadius;
}

std::vector<gpu::DirectionalLight> withSunAngle(std::vector<gpu::DirectionalLight> lights,
                                                float sunAngleDeg) {
  for (auto& l : lights) l.cosAngularRadius = sunCosAngularRadius(l.cosAngularRadius, sunAngleDeg);
  return lights;
}

}  // namespace wb::scene
