#include "scene/reflectors.h"

#include <algorithm>
#include <cmath>

namespace wb::scene {

bool isGlossyReflector(const gpu::Material& m) {
  const bool metal = m.metallic >= 0.5f && m.roughness <= 0.5f;
  const bool specularLayer = m.specularFactor > 0.0f && m.roughness <= 0.3f;
  return metal || specularLayer;
}

std::vector<glm::vec4> glossyReflectors(const Scene& scene, const std::vector<gpu::Material>& materials) {
  std::vector<glm::vec4> spheres;
  for (const auto& inst : scene.instances) {
    if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
    const auto& mesh = scene.meshes[inst.mesh];
    const bool glossy = std::any_of(mesh.primitives.begin(), mesh.primitives.end(), [&](const Primitive& p) {
      return p.material >= 0 && size_t(p.material) < materials.size() &&
             isGlossyReflector(materials[p.material]);
    });
    if (!glossy) continue;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    std::vector<glm::vec3> points;
    for (const auto& p : mesh.primitives) {
      for (const auto& v : p.vertices) {
        const glm::vec3 w = glm::vec3(inst.transform * glm::vec4(v.position, 1.0f));
        points.push_back(w);
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
      }
    }
    if (points.empty()) continue;
    const glm::vec3 centre = 0.5f * (lo + hi);
    float radius = 0.0f;
    for (const auto& p : points) radius = std::max(radius, glm::length(p - centre));
    if (!(radius > 0.0f) || !std::isfinite(radius)) continue;
    spheres.emplace_back(centre, radius * 1.0001f);  // every vertex inside, whatever the rounding
  }
  std::stable_sort(spheres.begin(), spheres.end(),
                   [](const glm::vec4& a, const glm::vec4& b) { return a.w > b.w; });
  if (spheres.size() > kMaxReflectors) spheres.resize(kMaxReflectors);
  return spheres;
}

}  // namespace wb::scene
