#include "test_scenes.h"

#include <cmath>

namespace wb::testing {
namespace {

gpu::Vertex vertex(glm::vec3 p, glm::vec3 n, glm::vec2 uv, glm::vec4 t) {
  gpu::Vertex v{};
  v.position = p;
  v.normal = n;
  v.u = uv.x;
  v.v = uv.y;
  v.tangent = t;
  return v;
}

}  // namespace

gpu::Material lambert(glm::vec3 albedo) {
  gpu::Material m{};
  m.baseColorFactor = glm::vec4(albedo, 1.0f);
  m.emissive = glm::vec3(0.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specularColorFactor = glm::vec3(1.0f);
  m.specularFactor = 0.0f;
  m.alphaCutoff = 0.5f;
  m.alphaMode = WB_ALPHA_OPAQUE;
  m.flags = 0;
  m.baseColorTexture = m.normalTexture = m.metallicRoughnessTexture = m.emissiveTexture = -1;
  m.normalScale = 1.0f;
  return m;
}

scene::Mesh quadMesh(float h, int material) {
  scene::Mesh mesh;
  mesh.name = "quad";
  scene::Primitive p;
  const glm::vec3 n(0, 1, 0);
  const glm::vec4 t(1, 0, 0, 1);
  p.vertices = {vertex({-h, 0, -h}, n, {0, 0}, t), vertex({h, 0, -h}, n, {1, 0}, t),
                vertex({h, 0, h}, n, {1, 1}, t), vertex({-h, 0, h}, n, {0, 1}, t)};
  p.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from +Y
  p.material = material;
  mesh.primitives.push_back(p);
  return mesh;
}

scene::Mesh boxMesh(glm::vec3 e, int material) {
  scene::Mesh mesh;
  mesh.name = "box";
  scene::Primitive p;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& n : normals) {
    glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    glm::vec3 v = glm::cross(n, u);
    uint32_t base = static_cast<uint32_t>(p.vertices.size());
    for (int i = 0; i < 4; ++i) {
      float a = (i == 1 || i == 2) ? 1.0f : -1.0f;
      float b = (i >= 2) ? 1.0f : -1.0f;
      glm::vec3 pos = (n + a * u + b * v) * e;
      p.vertices.push_back(vertex(pos, n, {a * 0.5f + 0.5f, b * 0.5f + 0.5f}, glm::vec4(u, 1.0f)));
    }
    // Winding chosen so the geometric normal (v1-v0)x(v2-v0) points along n.
    glm::vec3 g = glm::cross(p.vertices[base + 1].position - p.vertices[base].position,
                             p.vertices[base + 2].position - p.vertices[base].position);
    if (glm::dot(g, n) > 0) {
      p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    } else {
      p.indices.insert(p.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  }
  p.material = material;
  mesh.primitives.push_back(p);
  return mesh;
}

scene::Mesh sphereMesh(float r, int material, int segments, int rings) {
  scene::Mesh mesh;
  mesh.name = "sphere";
  scene::Primitive p;
  const float pi = 3.14159265358979f;
  for (int j = 0; j <= rings; ++j) {
    float theta = pi * j / rings;
    for (int i = 0; i <= segments; ++i) {
      float phi = 2 * pi * i / segments;
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      glm::vec3 t(-std::sin(phi), 0, std::cos(phi));
      p.vertices.push_back(vertex(n * r, n, {float(i) / segments, float(j) / rings}, glm::vec4(t, 1.0f)));
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      uint32_t a = j * (segments + 1) + i, b = a + segments + 1;
      // Outward winding: (a+1 - a) x (b - a) = d/dphi x d/dtheta points out for this parameterisation.
      p.indices.insert(p.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
  }
  p.material = material;
  mesh.primitives.push_back(p);
  return mesh;
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
