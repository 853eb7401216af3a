// Scenes built in code for GPU tests, with answers known analytically.
#pragma once
#include "render/renderer.h"
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

namespace wb::testing {

// A general material (glTF metallic-roughness; specularFactor 1 = the standard 4% dielectric).
gpu::Material pbr(glm::vec3 baseColor, float metallic, float roughness);

// The same scene with every length multiplied by k: vertex positions, instance translations, camera, bounds.
scene::Scene scaledScene(scene::Scene s, float k);

// Two spheres (glossy metal at x = -1.1, rough dielectric at x = +1.1) on a grey Lambert floor, seen from the
// front; meant for an environment map (no directional light).
scene::Scene makeEnvSpheresScene();

// Everything that tends to produce NaN/Inf: a floor seen at grazing angles, spheres of roughness 0 and 1
// (metal and dielectric), degenerate and zero-area triangles, zero normals, normal-mapped quads with missing,
// parallel and zero-handedness tangents, a single-sided quad seen from behind, and a directional light.
scene::Scene makeHardCasesScene();

}  // namespace wb::testing

namespace wb::testing {

// The camera ray through image point (px, py) in pixels of a w x h image, exactly as raygen builds it.
void cameraRay(const render::CameraState& cam, uint32_t w, uint32_t h, float px, float py, glm::vec3& origin,
               glm::vec3& dir);
// The slab test of a ray against the box lo..hi: the entry distance (0 inside), or -1 when it misses.
float hitBox(glm::vec3 origin, glm::vec3 dir, glm::vec3 lo, glm::vec3 hi);

}  // namespace wb::testing
