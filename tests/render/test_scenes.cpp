#include "test_scenes.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/procedural.h"

#include <cmath>

namespace wb::testing {
gpu::Material lambert(glm::vec3 albedo) {
  return scene::makeMaterial(albedo, 0.0f, 1.0f, 0.0f);
}

scene::Mesh quadMesh(float h, int material) {
  return scene::makeQuad(h, material);
}

scene::Mesh boxMesh(glm::vec3 e, int material) {
  return scene::makeBox(e, material);
}

scene::Mesh sphereMesh(float r, int material, int segments, int rings) {
  return scene::makeUvSphere(r, material, segments, rings);
}

ShadowScene makeShadowScene() {
  ShadowScene s;
  s.albedo = 0.8f;
  s.sunRadiance = 3.0f;
  s.sunDirection = glm::normalize(glm::vec3(0.5f, -1.0f, 0.3f));
  s.boxMin = glm::vec3(-0.5f, 1.0f, -0.5f);
  s.boxMax = glm::vec3(0.5f, 1.4f, 0.5f);
  auto& sc = s.scene;
  sc.sourcePath = "shadow-test";
  sc.materials = {lambert(glm::vec3(s.albedo)), lambert(glm::vec3(0.0f))};
  sc.materialNames = {"white", "black"};
  sc.meshes = {quadMesh(50.0f, 0), boxMesh((s.boxMax - s.boxMin) * 0.5f, 1)};
  sc.instances.push_back({0, glm::mat4(1.0f), "plane"});
  glm::mat4 t(1.0f);
  t[3] = glm::vec4((s.boxMin + s.boxMax) * 0.5f, 1.0f);
  sc.instances.push_back({1, t, "box"});
  gpu::DirectionalLight sun{};
  sun.direction = s.sunDirection;
  sun.cosAngularRadius = 1.0f;
  sun.radiance = glm::vec3(s.sunRadiance);
  sc.lights.push_back(sun);
  sc.camera.eye = glm::vec3(0.0f, 4.0f, 3.0f);
  sc.camera.target = glm::vec3(0.3f, 0.0f, 0.0f);
  sc.camera.up = glm::vec3(0, 1, 0);
  sc.camera.yfov = 0.9f;
  sc.bounds = {glm::vec3(-50, 0, -50), glm::vec3(50, 1.4f, 50)};
  return s;
}

}  // namespace wb::testing

namespace wb::testing {

scene::Scene makeFurnaceScene(gpu::Material material) {
  scene::Scene sc;
  sc.sourcePath = "furnace-test";
  sc.materials = {material};
  sc.materialNames = {"furnace"};
  sc.meshes = {sphereMesh(1.0f, 0, 64, 32)};
  sc.instances.push_back({0, glm::mat4(1.0f), "sphere"});
  sc.camera.eye = glm::vec3(0.0f, 0.0f, 2.2f);
  sc.camera.target = glm::vec3(0.0f);
  sc.camera.up = glm::vec3(0, 1, 0);
  sc.camera.yfov = 0.8f;
  sc.bounds = {glm::vec3(-1), glm::vec3(1)};
  return sc;
}

}  // namespace wb::testing

namespace wb::testing {

gpu::Material pbr(glm::vec3 baseColor, float metallic, float roughness) {
  return scene::makeMaterial(baseColor, metallic, roughness);
}

scene::Scene scaledScene(scene::Scene s, float k) {
  for (auto& mesh : s.meshes) {
    for (auto& prim : mesh.primitives) {
      for (auto& v : prim.vertices) v.position *= k;
    }
  }
  for (auto& inst : s.instances) inst.transform[3] = glm::vec4(glm::vec3(inst.transform[3]) * k, 1.0f);
  s.camera.eye *= k;
  s.camera.target *= k;
  s.bounds.min *= k;
  s.bounds.max *= k;
  return s;
}

namespace {

glm::mat4 translate(glm::vec3 t) {
  glm::mat4 m(1.0f);
  m[3] = glm::vec4(t, 1.0f);
  return m;
}

}  // namespace

scene::Scene makeEnvSpheresScene() {
  scene::Scene sc;
  sc.sourcePath = "env-spheres-test";
  sc.materials = {pbr(glm::vec3(0.95f, 0.8f, 0.55f), 1.0f, 0.3f),
                  pbr(glm::vec3(0.7f, 0.3f, 0.2f), 0.0f, 1.0f), lambert(glm::vec3(0.5f))};
  sc.materialNames = {"glossy-metal", "rough-dielectric", "floor"};
  sc.meshes = {sphereMesh(1.0f, 0, 32, 16), sphereMesh(1.0f, 1, 32, 16), quadMesh(6.0f, 2)};
  sc.instances.push_back({0, translate({-1.1f, 1.0f, 0.0f}), "glossy"});
  sc.instances.push_back({1, translate({1.1f, 1.0f, 0.0f}), "rough"});
  sc.instances.push_back({2, glm::mat4(1.0f), "floor"});
  sc.camera.eye = glm::vec3(0.0f, 1.6f, 4.2f);
  sc.camera.target = glm::vec3(0.0f, 0.8f, 0.0f);
  sc.camera.up = glm::vec3(0, 1, 0);
  sc.camera.yfov = 0.8f;
  sc.bounds = {glm::vec3(-6, 0, -6), glm::vec3(6, 2, 6)};
  return sc;
}

scene::Scene makeHardCasesScene() {
  scene::Scene sc;
  sc.sourcePath = "hard-cases-test";
  // 0-3: metal/dielectric at roughness 0 and 1; 4: floor; 5: normal-mapped; 6: single-sided Lambert.
  sc.materials = {pbr(glm::vec3(0.9f), 1.0f, 0.0f),
                  pbr(glm::vec3(0.9f), 1.0f, 1.0f),
                  pbr(glm::vec3(0.8f, 0.2f, 0.2f), 0.0f, 0.0f),
                  pbr(glm::vec3(0.2f, 0.8f, 0.2f), 0.0f, 1.0f),
                  pbr(glm::vec3(0.6f), 0.0f, 0.5f),
                  pbr(glm::vec3(0.7f), 0.0f, 0.4f),
                  lambert(glm::vec3(0.5f))};
  sc.materials[5].normalTexture = 0;
  sc.materialNames = {"metal-r0", "metal-r1",      "dielectric-r0", "dielectric-r1",
                      "floor",    "normal-mapped", "back"};
  // A 1x1 tangent-space normal map tilted towards +T (so a bad frame would matter).
  scene::Image img;
  img.name = "tilted-normal";
  img.width = img.height = 1;
  img.rgba8 = {230, 128, 160, 255};
  sc.images = {img};
  sc.textures = {{0, -1}};
  sc.textureIsSrgb = {false};

  sc.meshes.push_back(quadMesh(50.0f, 4));                                       // 0: floor
  for (int m = 0; m < 4; ++m) sc.meshes.push_back(sphereMesh(0.4f, m, 24, 12));  // 1-4
  // 5: degenerate triangles: repeated indices, collinear vertices, a 1e-20-area sliver, zero normals.
  {
    scene::Mesh mesh;
    mesh.name = "degenerate";
    scene::Primitive p;
    auto vtx = [](glm::vec3 pos, glm::vec3 n) {
      gpu::Vertex v{};
      v.position = pos;
      v.normal = n;
      return v;
    };
    p.vertices = {vtx({0, 0, 0}, {0, 0, 1}),     vtx({1, 0, 0}, {0, 0, 1}),
                  vtx({2, 0, 0}, {0, 0, 1}),     vtx({0, 1, 0}, {0, 0, 0}),
                  vtx({1, 1, 0}, {0, 0, 0}),     vtx({0.5f, 1.0f + 1e-10f, 0}, {0, 0, 0}),
                  vtx({0, 0.5f, 0}, {0, 0, -1}), vtx({1, 0.5f, 0}, {0, 0, 1})};
    p.indices = {0, 0, 0, 0, 1, 1, 0, 1, 2,  // zero-area: repeated, collinear
                 3, 4, 5,                    // sliver
                 3, 4, 0,                    // zero normals at two vertices
                 6, 7, 4};                   // opposite normals: interpolates through zero
    p.material = 4;
    mesh.primitives.push_back(p);
    sc.meshes.push_back(mesh);
  }
  // 6-8: normal-mapped quads (facing +Z after the instance rotation) with missing, parallel and w = 0
  // tangents.
  for (glm::vec4 t : {glm::vec4(0.0f), glm::vec4(0, 1, 0, 1), glm::vec4(1, 0, 0, 0)}) {
    scene::Mesh q = quadMesh(0.3f, 5);
    for (auto& v : q.primitives[0].vertices) v.tangent = t;
    sc.meshes.push_back(q);
  }
  sc.meshes.push_back(quadMesh(0.4f, 6));  // 9: single-sided, seen from behind

  sc.instances.push_back({0, glm::mat4(1.0f), "floor"});
  for (int m = 0; m < 4; ++m)
    sc.instances.push_back({1 + m, translate({-1.8f + 1.2f * m, 0.4f, -1.0f}), "s"});
  sc.instances.push_back({5, translate({-0.5f, 0.9f, 0.5f}), "degenerate"});
  // quadMesh lies in y = 0 with normal +Y: rotate +90 degrees about X so it faces +Z (the camera).
  glm::mat4 face(1.0f);
  face[1] = glm::vec4(0, 0, 1, 0);
  face[2] = glm::vec4(0, -1, 0, 0);
  for (int i = 0; i < 3; ++i) {
    glm::mat4 t = face;
    t[3] = glm::vec4(-1.0f + 0.8f * i, 1.6f, 0.0f, 1.0f);
    sc.instances.push_back({6 + i, t, "normal-mapped"});
  }
  glm::mat4 away(1.0f);  // rotate -90 degrees about X: faces -Z, away from the camera
  away[1] = glm::vec4(0, 0, -1, 0);
  away[2] = glm::vec4(0, 1, 0, 0);
  away[3] = glm::vec4(1.6f, 1.5f, 0.3f, 1.0f);
  sc.instances.push_back({9, away, "back-face"});

  gpu::DirectionalLight sun{};
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.cosAngularRadius = 1.0f;
  sun.radiance = glm::vec3(2.0f);
  sc.lights.push_back(sun);
  // Low camera: the floor is seen at grazing angles towards the horizon.
  sc.camera.eye = glm::vec3(0.0f, 0.25f, 4.0f);
  sc.camera.target = glm::vec3(0.0f, 0.6f, 0.0f);
  sc.camera.up = glm::vec3(0, 1, 0);
  sc.camera.yfov = 1.0f;
  sc.bounds = {glm::vec3(-50, 0, -50), glm::vec3(50, 2, 50)};
  return sc;
}

}  // namespace wb::testing

namespace wb::testing {

void cameraRay(const render::CameraState& cam, uint32_t w, uint32_t h, float px, float py, glm::vec3& origin,
               glm::vec3& dir) {
  glm::mat4 proj = glm::perspective(cam.yfov, float(w) / float(h), cam.znear, 1000.0f);
  proj[1][1] *= -1.0f;
  const glm::vec2 ndc(px / w * 2.0f - 1.0f, py / h * 2.0f - 1.0f);
  glm::vec4 target = glm::inverse(proj) * glm::vec4(ndc, 1.0f, 1.0f);
  glm::mat4 vi = glm::inverse(cam.view);
  origin = glm::vec3(vi * glm::vec4(0, 0, 0, 1));
  dir = glm::normalize(glm::vec3(vi * glm::vec4(glm::normalize(glm::vec3(target) / target.w), 0.0f)));
}

float hitBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
  float t0 = 0.0f, t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    float inv = 1.0f / d[a];
    float tn = (lo[a] - o[a]) * inv, tf = (hi[a] - o[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  return t0 <= t1 ? t0 : -1.0f;
}

}  // namespace wb::testing
