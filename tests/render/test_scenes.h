// Scenes built in code for GPU tests, with answers known analytically.
#pragma once
#include "scene/scene.h"

namespace wb::testing {

gpu::Material lambert(glm::vec3 albedo);  // roughness 1, metallic 0, specularFactor 0: BRDF = albedo / pi
scene::Mesh quadMesh(float halfSize, int material);       // in the y = 0 plane, normal +Y
scene::Mesh boxMesh(glm::vec3 halfExtent, int material);  // outward normals
scene::Mesh sphereMesh(float radius, int material, int segments = 48, int rings = 24);

// A white plane (albedo 0.8) at y = 0, a black box floating above it, a sun of radiance `sunRadiance`
// travelling along `sunDirection`, a camera looking down at the plane. Environment should be black.
struct ShadowScene {
  scene::Scene scene;
  glm::vec3 boxMin, boxMax;
  glm::vec3 sunDirection;
  float albedo;
  float sunRadiance;
};
ShadowScene makeShadowScene();

}  // namespace wb::testing

namespace wb::testing {
// A white Lambertian sphere (specularFactor 0) alone in the scene, camera framing it: in a uniform
// environment of radiance 1 every pixel converges to exactly 1 (the white furnace).
scene::Scene makeFurnaceScene(gpu::Material material);
}  // namespace wb::testing
