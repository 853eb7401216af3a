#include <gtest/gtest.h>

#include "scene/vertex_generation.h"

namespace wb::scene {
namespace {

gpu::Vertex vertex(glm::vec3 p, float u, float v) {
  gpu::Vertex out{};
  out.position = p;
  out.u = u;
  out.v = v;
  return out;
}

TEST(VertexGeneration, AreaWeightedNormalsOfAFold) {
  // Two triangles sharing the edge 0-1: a large one in the XY plane (normal +Z, area 2) and a small one in
  // the XZ plane (normal +Y, area 0.5). The shared vertices get (0, 0.5, 2) normalised.
  std::vector<gpu::Vertex> vertices = {vertex({0, 0, 0}, 0, 0), vertex({2, 0, 0}, 1, 0),
                                       vertex({0, 2, 0}, 0, 1), vertex({0, 0, -0.5f}, 0, 0)};
  const std::vector<uint32_t> indices = {0, 1, 2, 0, 1, 3};
  generateNormals(vertices, indices);
  const glm::vec3 expected = glm::normalize(glm::vec3(0.0f, 0.5f * 2.0f, 2.0f * 2.0f));
  EXPECT_NEAR(vertices[0].normal.y, expected.y, 1e-6f);
  EXPECT_NEAR(vertices[0].normal.z, expected.z, 1e-6f);
  EXPECT_NEAR(vertices[2].normal.z, 1.0f, 1e-6f);
  EXPECT_NEAR(vertices[3].normal.y, 1.0f, 1e-6f);
}

TEST(VertexGeneration, TangentsFollowUAndHandednessFollowsV) {
  std::vector<gpu::Vertex> vertices = {vertex({0, 0, 0}, 0, 0), vertex({1, 0, 0}, 1, 0),
                                       vertex({0, 1, 0}, 0, 1)};
  const std::vector<uint32_t> indices = {0, 1, 2};
  generateNormals(vertices, indices);
  generateTangents(vertices, indices);
  for (const gpu::Vertex& v : vertices) {
    EXPECT_NEAR(v.tangent.x, 1.0f, 1e-6f);
    EXPECT_NEAR(v.tangent.y, 0.0f, 1e-6f);
    EXPECT_EQ(v.tangent.w, 1.0f);  // cross(+Z, +X) = +Y = direction of increasing v
  }
  // Mirror V: handedness flips.
  for (gpu::Vertex& v : vertices) v.v = -v.v;
  generateTangents(vertices, indices);
  for (const gpu::Vertex& v : vertices) EXPECT_EQ(v.tangent.w, -1.0f);
}

TEST(VertexGeneration, DegenerateUvsStillGiveAPerpendicularUnitTangent) {
  std::vector<gpu::Vertex> vertices = {vertex({0, 0, 0}, 0, 0), vertex({1, 0, 0}, 0, 0),
                                       vertex({0, 1, 0}, 0, 0)};
  const std::vector<uint32_t> indices = {0, 1, 2};
  generateNormals(vertices, indices);
  generateTangents(vertices, indices);
  for (const gpu::Vertex& v : vertices) {
    EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
  }
}

}  // namespace
}  // namespace wb::scene
