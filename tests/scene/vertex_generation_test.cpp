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

TEST(VertexGeneration, FlatNormalsOfAFold) {
  // Two triangles sharing the edge 0-1, one in the XY plane (normal +Z) and one in the XZ plane (normal +Y):
  // glTF asks for flat normals, so the shared corners are split and each triangle keeps its face normal.
  std::vector<gpu::Vertex> vertices = {vertex({0, 0, 0}, 0, 0), vertex({2, 0, 0}, 1, 0),
                                       vertex({0, 2, 0}, 0, 1), vertex({0, 0, -0.5f}, 0, 0)};
  std::vector<uint32_t> indices = {0, 1, 2, 0, 1, 3, 0, 0, 1};  // the last one is degenerate
  makeFlatNormals(vertices, indices);
  ASSERT_EQ(vertices.size(), 9u);
  EXPECT_EQ(indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(vertices[i].normal.z, 1.0f, 1e-6f) << i;
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(vertices[i].normal.y, 1.0f, 1e-6f) << i;
  for (int i = 6; i < 9; ++i) EXPECT_EQ(vertices[i].normal, glm::vec3(0, 1, 0)) << i;
  EXPECT_EQ(vertices[4].position, glm::vec3(2, 0, 0));  // corners copied with their attributes
  EXPECT_EQ(vertices[4].u, 1.0f);
}

TEST(VertexGeneration, TangentsFollowUAndHandednessFollowsV) {
  std::vector<gpu::Vertex> vertices = {vertex({0, 0, 0}, 0, 0), vertex({1, 0, 0}, 1, 0),
                                       vertex({0, 1, 0}, 0, 1)};
  std::vector<uint32_t> indices = {0, 1, 2};
  makeFlatNormals(vertices, indices);
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
  std::vector<uint32_t> indices = {0, 1, 2};
  makeFlatNormals(vertices, indices);
  generateTangents(vertices, indices);
  for (const gpu::Vertex& v : vertices) {
    EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-6f);
  }
}

}  // namespace
}  // namespace wb::scene
