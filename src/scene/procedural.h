// Scenes and meshes generated in code: benchmark scenes (e.g. a heavy scene of over a million triangles) and
// the building blocks tests use.
#pragma once
#include "scene/scene.h"

namespace wb::scene {

gpu::Vertex makeVertex(glm::vec3 position, glm::vec3 normal, glm::vec2 uv, glm::vec4 tangent);
// glTF metallic-roughness with KHR_materials_specular's factor (0 = a pure Lambertian when metallic is 0).
gpu::Material makeMaterial(glm::vec3 baseColor, float metallic, float roughness, float specularFactor = 1.0f);
Mesh makeQuad(float halfSize, int material);       // y = 0 plane, normal +Y
Mesh makeBox(glm::vec3 halfExtent, int material);  // centred at the origin, outward winding
Mesh makeUvSphere(float radius, int material, int segments,
                  int rings);  // 2 * segments * (rings - 1) triangles
// A floor, a sun and a bumpy sphere tessellated to at least `minTriangles` triangles (one BLAS), framed by
// the camera: the heavy scene of the performance suite.
Scene makeHeavyScene(size_t minTriangles);

}  // namespace wb::scene
