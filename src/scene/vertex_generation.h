// Fills in vertex attributes a glTF primitive did not provide (or provided broken).
#pragma once

#include <cstdint>
#include <vector>

#include "shared/scene_types.h"

namespace wb::scene {

// Flat normals, as glTF requires when a primitive has no NORMAL: every triangle gets its own three vertices
// (copies of its corners) carrying its face normal, and the indices become 0, 1, 2, ... Degenerate triangles
// get +Y.
void makeFlatNormals(std::vector<gpu::Vertex>& vertices, std::vector<uint32_t>& indices);

// Tangents from UV derivatives (accumulated per vertex, Gram-Schmidt against the normal, handedness in w so
// that cross(normal, tangent.xyz) * w points along +v). Needs normals and UVs. Vertices without usable UV
// derivatives get an arbitrary unit tangent perpendicular to the normal (w = 1).
void generateTangents(std::vector<gpu::Vertex>& vertices, const std::vector<uint32_t>& indices);

// Any unit vector perpendicular to the unit vector n.
glm::vec3 anyPerpendicular(const glm::vec3& n);

}  // namespace wb::scene
