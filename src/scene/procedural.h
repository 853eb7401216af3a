// Scenes and meshes generated in code: benchmark scenes (e.g. a heavy scene of over a million triangles) and
// the building blocks tests use.
#pragma once
#include "scene/scene.h"

namespace wb::scene {

gpu::Material makeMaterial(glm::vec3 baseColor, float metallic, float roughness);
Mesh makeQuad(float halfSize, int material);                    // y = 0 plane, normal +Y
Mesh makeUvSphere(float radius, int material, int segments, int rings);  // 2 * segments * (rings - 1) triangles
// A floor, a sun and a bumpy sphere tessellated to at least `minTriangles` triangles (one BLAS), framed by the
// camera: the heavy scene of the performance suite.
Scene makeHeavyScene(size_t minTriangles);

}  // namespace wb::scene
