#include "scene/vertex_generation.h"

#include <cmath>

namespace wb::scene {

glm::vec3 anyPerpendicular(const glm::vec3& n) {
  const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  return glm::normalize(glm::cross(n, axis));
}

void makeFlatNormals(std::vector<gpu::Vertex>& vertices, std::vector<uint32_t>& indices) {
  std::vector<gpu::Vertex> flat;
  flat.reserve(indices.size() / 3 * 3);
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const gpu::Vertex& a = vertices[indices[t]];
    const gpu::Vertex& b = vertices[indices[t + 1]];
    const gpu::Vertex& c = vertices[indices[t + 2]];
    const glm::dvec3 p0(a.position), p1(b.position), p2(c.position);
    const glm::dvec3 face = glm::cross(p1 - p0, p2 - p0);
    const double length = glm::length(face);
    const glm::vec3 n = length > 0.0 && std::isfinite(length) ? glm::vec3(face / length) : glm::vec3(0, 1, 0);
    for (const gpu::Vertex* v : {&a, &b, &c}) {
      flat.push_back(*v);
      flat.back().normal = n;
    }
  }
  vertices = std::move(flat);
  indices.resize(vertices.size());
  for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
}

void generateTangents(std::vector<gpu::Vertex>& vertices, const std::vector<uint32_t>& indices) {
  std::vector<glm::dvec3> tangentSums(vertices.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> bitangentSums(vertices.size(), glm::dvec3(0.0));
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t idx[3] = {indices[t], indices[t + 1], indices[t + 2]};
    const gpu::Vertex& v0 = vertices[idx[0]];
    const gpu::Vertex& v1 = vertices[idx[1]];
    const gpu::Vertex& v2 = vertices[idx[2]];
    const glm::dvec3 e1 = glm::dvec3(v1.position) - glm::dvec3(v0.position);
    const glm::dvec3 e2 = glm::dvec3(v2.position) - glm::dvec3(v0.position);
    const double du1 = double(v1.u) - v0.u, dv1 = double(v1.v) - v0.v;
    const double du2 = double(v2.u) - v0.u, dv2 = double(v2.v) - v0.v;
    const double det = du1 * dv2 - du2 * dv1;
    if (!(std::abs(det) > 1e-20) || !std::isfinite(det)) continue;
    // Weight by area: the unnormalised derivatives scaled by |det| are proportional to the triangle's area.
    const double sign = det > 0.0 ? 1.0 : -1.0;
    const glm::dvec3 dPdu = (e1 * dv2 - e2 * dv1) * sign;
    const glm::dvec3 dPdv = (e2 * du1 - e1 * du2) * sign;
    for (uint32_t i : idx) {
      tangentSums[i] += dPdu;
      bitangentSums[i] += dPdv;
    }
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    const glm::dvec3 n(vertices[i].normal);
    glm::dvec3 t = tangentSums[i] - n * glm::dot(n, tangentSums[i]);
    const double length = glm::length(t);
    if (!(length > 1e-12) || !std::isfinite(length)) {
      vertices[i].tangent = glm::vec4(anyPerpendicular(vertices[i].normal), 1.0f);
      continue;
    }
    t /= length;
    const double handedness = glm::dot(glm::cross(n, t), bitangentSums[i]) < 0.0 ? -1.0 : 1.0;
    vertices[i].tangent = glm::vec4(glm::vec3(t), static_cast<float>(handedness));
  }
}

}  // namespace wb::scene
