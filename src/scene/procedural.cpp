#include "scene/procedural.h"

#include <cmath>

namespace wb::scene {
gpu::Vertex makeVertex(glm::vec3 p, glm::vec3 n, glm::vec2 uv, glm::vec4 t) {
  gpu::Vertex v{};
  v.position = p;
  v.normal = n;
  v.u = uv.x;
  v.v = uv.y;
  v.tangent = t;
  return v;
}

gpu::Material makeMaterial(glm::vec3 baseColor, float metallic, float roughness, float specularFactor) {
  gpu::Material m{};
  m.baseColorFactor = glm::vec4(baseColor, 1.0f);
  m.emissive = glm::vec3(0.0f);
  m.metallic = metallic;
  m.roughness = roughness;
  m.specularColorFactor = glm::vec3(1.0f);
  m.specularFactor = specularFactor;
  m.alphaCutoff = 0.5f;
  m.alphaMode = WB_ALPHA_OPAQUE;
  m.flags = 0;
  m.baseColorTexture = m.normalTexture = m.metallicRoughnessTexture = m.emissiveTexture = -1;
  m.normalScale = 1.0f;
  return m;
}

Mesh makeQuad(float h, int material) {
  Mesh mesh;
  mesh.name = "quad";
  Primitive p;
  const glm::vec3 n(0, 1, 0);
  const glm::vec4 t(1, 0, 0, 1);
  p.vertices = {makeVertex({-h, 0, -h}, n, {0, 0}, t), makeVertex({h, 0, -h}, n, {1, 0}, t),
                makeVertex({h, 0, h}, n, {1, 1}, t), makeVertex({-h, 0, h}, n, {0, 1}, t)};
  p.indices = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from +Y
  p.material = material;
  mesh.primitives.push_back(std::move(p));
  return mesh;
}

Mesh makeBox(glm::vec3 e, int material) {
  Mesh mesh;
  mesh.name = "box";
  Primitive p;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& n : normals) {
    const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 v = glm::cross(n, u);
    const uint32_t base = static_cast<uint32_t>(p.vertices.size());
    for (int i = 0; i < 4; ++i) {
      const float a = (i == 1 || i == 2) ? 1.0f : -1.0f;
      const float b = (i >= 2) ? 1.0f : -1.0f;
      p.vertices.push_back(
          makeVertex((n + a * u + b * v) * e, n, {a * 0.5f + 0.5f, b * 0.5f + 0.5f}, glm::vec4(u, 1)));
    }
    // Winding chosen so the geometric normal (v1-v0)x(v2-v0) points along n.
    const glm::vec3 g = glm::cross(p.vertices[base + 1].position - p.vertices[base].position,
                                   p.vertices[base + 2].position - p.vertices[base].position);
    if (glm::dot(g, n) > 0) {
      p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    } else {
      p.indices.insert(p.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  }
  p.material = material;
  mesh.primitives.push_back(std::move(p));
  return mesh;
}

Mesh makeUvSphere(float r, int material, int segments, int rings) {
  Mesh mesh;
  mesh.name = "sphere";
  Primitive p;
  const float pi = 3.14159265358979f;
  p.vertices.reserve(size_t(segments + 1) * (rings + 1));
  for (int j = 0; j <= rings; ++j) {
    const float theta = pi * j / rings;
    for (int i = 0; i <= segments; ++i) {
      const float phi = 2 * pi * i / segments;
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const glm::vec3 t(-std::sin(phi), 0, std::cos(phi));
      p.vertices.push_back(makeVertex(n * r, n, {float(i) / segments, float(j) / rings}, glm::vec4(t, 1.0f)));
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      const uint32_t a = j * (segments + 1) + i, b = a + segments + 1;
      if (j > 0) p.indices.insert(p.indices.end(), {a, a + 1, b});  // outward: d/dphi x d/dtheta
      if (j < rings - 1) p.indices.insert(p.indices.end(), {a + 1, b + 1, b});
    }
  }
  p.material = material;
  mesh.primitives.push_back(std::move(p));
  return mesh;
}

Scene makeHeavyScene(size_t minTriangles) {
  Scene s;
  s.sourcePath = "generated:heavy-" + std::to_string(minTriangles);
  s.materials = {makeMaterial(glm::vec3(0.7f), 0.0f, 0.8f),
                 makeMaterial(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.3f)};
  s.materialNames = {"floor", "bumpy metal"};
  s.meshes.push_back(makeQuad(20.0f, 0));
  // segments = 2 * rings gives 4 * rings * (rings - 1) triangles.
  const int rings = int(std::ceil(std::sqrt(double(minTriangles) / 4.0))) + 1;
  Mesh sphere = makeUvSphere(1.0f, 1, 2 * rings, rings);
  // Bumps: displace along the normal (the normals stay the sphere's: shading detail comes from geometry).
  for (auto& v : sphere.primitives[0].vertices) {
    const float bump = 0.03f * std::sin(40.0f * v.u * 6.2831853f) * std::sin(20.0f * v.v * 3.14159265f);
    v.position *= 1.0f + bump;
  }
  s.meshes.push_back(std::move(sphere));
  s.instances.push_back({0, glm::mat4(1.0f), "floor"});
  glm::mat4 t(1.0f);
  t[3] = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
  s.instances.push_back({1, t, "bumpy sphere"});
  gpu::DirectionalLight sun{};
  sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.3f));
  sun.cosAngularRadius = 1.0f;
  sun.radiance = glm::vec3(3.0f);
  s.lights.push_back(sun);
  s.camera.eye = glm::vec3(0.0f, 1.6f, 3.5f);
  s.camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
  s.camera.up = glm::vec3(0, 1, 0);
  s.camera.yfov = 0.7f;
  s.bounds = {glm::vec3(-20, 0, -20), glm::vec3(20, 2.1f, 20)};
  return s;
}

}  // namespace wb::scene
