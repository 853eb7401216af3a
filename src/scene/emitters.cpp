#include "scene/emitters.h"

#include <cmath>

namespace wb::scene {

float emitterLuminance(const gpu::Material& m) {
  return 0.2126f * m.emissive.x + 0.7152f * m.emissive.y + 0.0722f * m.emissive.z;
}

std::vector<gpu::EmissiveTriangle> emissiveTriangles(const Scene& scene) {
  return emissiveTriangles(scene, scene.materials);
}

std::vector<gpu::EmissiveTriangle> emissiveTriangles(const Scene& scene,
                                                     const std::vector<gpu::Material>& materials) {
  std::vector<gpu::EmissiveTriangle> out;
  for (const auto& inst : scene.instances) {
    if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
    for (const auto& prim : scene.meshes[inst.mesh].primitives) {
      if (prim.material < 0 || size_t(prim.material) >= materials.size()) continue;
      const auto& m = materials[prim.material];
      // A non-finite emission is no light to sample: paths that hit it are dropped and counted instead.
      const float luminance = emitterLuminance(m);
      if (!(luminance > 0.0f) || !std::isfinite(luminance)) continue;
      for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        gpu::EmissiveTriangle e{};
        const gpu::Vertex* v[3] = {&prim.vertices[prim.indices[t]], &prim.vertices[prim.indices[t + 1]],
                                   &prim.vertices[prim.indices[t + 2]]};
        e.p0 = glm::vec3(inst.transform * glm::vec4(v[0]->position, 1.0f));
        e.p1 = glm::vec3(inst.transform * glm::vec4(v[1]->position, 1.0f));
        e.p2 = glm::vec3(inst.transform * glm::vec4(v[2]->position, 1.0f));
        e.area = 0.5f * glm::length(glm::cross(e.p1 - e.p0, e.p2 - e.p0));
        if (!(e.area > 0.0f) || !std::isfinite(e.area)) continue;
        e.uv0 = {v[0]->u, v[0]->v};
        e.uv1 = {v[1]->u, v[1]->v};
        e.uv2 = {v[2]->u, v[2]->v};
        e.materialIndex = uint32_t(prim.material);
        e.doubleSided = (m.flags & WB_MATERIAL_DOUBLE_SIDED) ? 1u : 0u;
        out.push_back(e);
      }
    }
  }
  return out;
}

std::vector<double> emitterWeights(const Scene& scene, const std::vector<gpu::EmissiveTriangle>& emitters) {
  return emitterWeights(scene.materials, emitters);
}

std::vector<double> emitterWeights(const std::vector<gpu::Material>& materials,
                                   const std::vector<gpu::EmissiveTriangle>& emitters) {
  std::vector<double> w;
  w.reserve(emitters.size());
  for (const auto& e : emitters) w.push_back(double(emitterLuminance(materials[e.materialIndex])) * e.area);
  return w;
}

}  // namespace wb::scene
