#include "app/window/pixel_picker.h"

#include <cmath>
#include <limits>
#include <glm/gtc/matrix_transform.hpp>

namespace wb::app {

void cameraRay(const render::CameraState& camera, uint32_t width, uint32_t height, float px, float py,
               glm::vec3& origin, glm::vec3& direction) {
  const float aspect = float(width) / float(height);
  glm::mat4 proj = glm::perspective(camera.yfov, aspect, camera.znear, 1000.0f);
  proj[1][1] *= -1.0f;
  const glm::mat4 viewInv = glm::inverse(camera.view);
  const glm::mat4 projInv = glm::inverse(proj);
  const glm::vec2 ndc = glm::vec2(px / float(width), py / float(height)) * 2.0f - 1.0f;
  const glm::vec4 target = projInv * glm::vec4(ndc.x, ndc.y, 1.0f, 1.0f);
  origin = glm::vec3(viewInv * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  direction =
      glm::normalize(glm::vec3(viewInv * glm::vec4(glm::normalize(glm::vec3(target) / target.w), 0.0f)));
}

std::optional<PickResult> pickRay(const scene::Scene& scene, const glm::vec3& origin,
                                  const glm::vec3& direction) {
  std::optional<PickResult> best;
  float bestT = std::numeric_limits<float>::max();
  for (size_t ii = 0; ii < scene.instances.size(); ++ii) {
    const auto& inst = scene.instances[ii];
    if (inst.mesh < 0) continue;
    const auto& mesh = scene.meshes[size_t(inst.mesh)];
    // Intersect in object space: the ray transformed by the inverse; t stays a world-space parameter.
    const glm::mat4 inv = glm::inverse(inst.transform);
    const glm::vec3 o = glm::vec3(inv * glm::vec4(origin, 1.0f));
    const glm::vec3 d = glm::vec3(inv * glm::vec4(direction, 0.0f));
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const auto& prim = mesh.primitives[pi];
      for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        const glm::vec3 a = prim.vertices[prim.indices[t]].position;
        const glm::vec3 b = prim.vertices[prim.indices[t + 1]].position;
        const glm::vec3 c = prim.vertices[prim.indices[t + 2]].position;
        const glm::vec3 e1 = b - a, e2 = c - a;
        const glm::vec3 p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::fabs(det) < 1e-12f) continue;
        const float invDet = 1.0f / det;
        const glm::vec3 s = o - a;
        const float u = glm::dot(s, p) * invDet;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(d, q) * invDet;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float dist = glm::dot(e2, q) * invDet;
        if (dist <= 1e-6f || dist >= bestT) continue;
        bestT = dist;
        PickResult r;
        r.instance = int(ii);
        r.mesh = inst.mesh;
        r.primitive = int(pi);
        r.triangle = int(t / 3);
        r.material = prim.material;
        r.nodeName = inst.nodeName;
        r.meshName = mesh.name;
        if (prim.material >= 0 && size_t(prim.material) < scene.materialNames.size())
          r.materialName = scene.materialNames[size_t(prim.material)];
        r.barycentrics = {1.0f - u - v, u, v};
        const auto& va = prim.vertices[prim.indices[t]];
        const auto& vb = prim.vertices[prim.indices[t + 1]];
        const auto& vc = prim.vertices[prim.indices[t + 2]];
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
        r.shadingNormal =
            glm::normalize(normalMatrix * (va.normal * r.barycentrics.x + vb.normal * u + vc.normal * v));
        r.geometricNormal = glm::normalize(normalMatrix * glm::cross(e1, e2));
        r.uv =
            glm::vec2(va.u, va.v) * r.barycentrics.x + glm::vec2(vb.u, vb.v) * u + glm::vec2(vc.u, vc.v) * v;
        r.position = origin + direction * dist;
        r.distance = dist * glm::length(direction);
        best = r;
      }
    }
  }
  return best;
}

}  // namespace wb::app
