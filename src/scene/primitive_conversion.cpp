#include "scene/primitive_conversion.h"

#include <cmath>

#include "scene/accessor_reader.h"
#include "scene/vertex_generation.h"

namespace wb::scene {
namespace {

const char* modeName(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return "POINTS";
    case TINYGLTF_MODE_LINE:
      return "LINES";
    case TINYGLTF_MODE_LINE_LOOP:
      return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP:
      return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_STRIP:
      return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN:
      return "TRIANGLE_FAN";
    default:
      return "unknown";
  }
}

// Strips and fans become lists (they are triangles too); the winding of every other strip triangle is flipped
// back to counter-clockwise as the spec describes.
std::vector<uint32_t> toTriangleList(const std::vector<uint32_t>& indices, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indices;
  std::vector<uint32_t> list;
  for (size_t i = 2; i < indices.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      const bool odd = (i % 2) == 1;
      list.insert(list.end(),
                  {indices[i - 2], odd ? indices[i] : indices[i - 1], odd ? indices[i - 1] : indices[i]});
    } else {
      list.insert(list.end(), {indices[0], indices[i - 1], indices[i]});
    }
  }
  return list;
}

bool allUnitLength(const std::vector<float>& values, size_t stride) {
  for (size_t i = 0; i + 2 < values.size(); i += stride) {
    const float length2 =
        values[i] * values[i] + values[i + 1] * values[i + 1] + values[i + 2] * values[i + 2];
    if (!std::isfinite(length2) || std::abs(length2 - 1.0f) > 0.1f) return false;
  }
  return true;
}

bool allFinite(const std::vector<float>& values) {
  for (float value : values) {
    if (!std::isfinite(value)) return false;
  }
  return true;
}

int attribute(const tinygltf::Primitive& primitive, const char* name) {
  const auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -2 : it->second;
}

}  // namespace

std::optional<Primitive> convertPrimitive(LoadContext& ctx, const tinygltf::Primitive& source,
                                          const std::string& where) {
  const int mode = source.mode < 0 ? TINYGLTF_MODE_TRIANGLES : source.mode;
  if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
      mode != TINYGLTF_MODE_TRIANGLE_FAN) {
    ctx.warn(where + ": primitive mode " + modeName(mode) + " (" + std::to_string(mode) +
             ") unsupported, primitive skipped");
    return std::nullopt;
  }
  const int positionAccessor = attribute(source, "POSITION");
  if (positionAccessor == -2) {
    ctx.warn(where + ": no POSITION attribute, primitive skipped");
    return std::nullopt;
  }
  if (source.material < -1 ||
      (source.material >= 0 && static_cast<size_t>(source.material) >= ctx.model().materials.size())) {
    ctx.fail(where + " refers to material " + std::to_string(source.material) + ", which does not exist");
  }
  for (const auto& [name, index] : source.attributes) {
    if (name == "COLOR_0") ctx.warn(where + ": vertex colours (COLOR_0) unsupported, ignored");
    if (name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0) {
      ctx.warn(where + ": skinning attributes (" + name + ") ignored");
    }
  }
  if (!source.targets.empty()) ctx.warn(where + ": morph targets unsupported, ignored");

  const std::vector<float> positions = readFloatAccessor(ctx, positionAccessor, 3, where + " POSITION");
  if (!allFinite(positions)) ctx.fail(where + ": POSITION contains NaN or infinite values");
  const size_t vertexCount = positions.size() / 3;

  Primitive primitive;
  primitive.material = source.material;
  primitive.vertices.resize(vertexCount);
  for (size_t i = 0; i < vertexCount; ++i) {
    gpu::Vertex& vertex = primitive.vertices[i];
    vertex.position = glm::vec3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    vertex.u = vertex.v = 0.0f;
    vertex.normal = glm::vec3(0.0f);
    vertex.tangent = glm::vec4(0.0f);
  }

  // Indices (sequential when absent), then checked and turned into a triangle list.
  std::vector<uint32_t> indices;
  if (source.indices >= 0) {
    indices = readIndexAccessor(ctx, source.indices, where + " indices");
  } else if (source.indices != -1) {
    ctx.fail(where + " has invalid indices accessor " + std::to_string(source.indices));
  } else {
    indices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<uint32_t>(i);
  }
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= vertexCount) {
      ctx.fail(where + ": index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
               " is out of range (" + std::to_string(vertexCount) + " vertices)");
    }
  }
  indices = toTriangleList(indices, mode);
  if (indices.size() % 3 != 0) {
    ctx.warn(where + ": index count not a multiple of 3, trailing indices dropped");
    indices.resize(indices.size() - indices.size() % 3);
  }
  primitive.indices = std::move(indices);

  const int uvAccessor = attribute(source, "TEXCOORD_0");
  const bool hasUvs = uvAccessor != -2;
  if (hasUvs) {
    const std::vector<float> uvs = readFloatAccessor(ctx, uvAccessor, 2, where + " TEXCOORD_0");
    if (uvs.size() / 2 != vertexCount) ctx.fail(where + ": TEXCOORD_0 count differs from POSITION count");
    if (!allFinite(uvs)) ctx.fail(where + ": TEXCOORD_0 contains NaN or infinite values");
    for (size_t i = 0; i < vertexCount; ++i) {
      primitive.vertices[i].u = uvs[2 * i];
      primitive.vertices[i].v = uvs[2 * i + 1];
    }
  }

  const int normalAccessor = attribute(source, "NORMAL");
  bool normalsValid = false;
  if (normalAccessor != -2) {
    const std::vector<float> normals = readFloatAccessor(ctx, normalAccessor, 3, where + " NORMAL");
    if (normals.size() / 3 != vertexCount) ctx.fail(where + ": NORMAL count differs from POSITION count");
    normalsValid = allUnitLength(normals, 3);
    if (normalsValid) {
      for (size_t i = 0; i < vertexCount; ++i) {
        primitive.vertices[i].normal =
            glm::normalize(glm::vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]));
      }
    } else {
      ctx.warn(where + ": NORMAL has non-unit, zero or non-finite vectors, normals regenerated");
    }
  }
  if (!normalsValid) {
    makeFlatNormals(primitive.vertices, primitive.indices);
    primitive.generatedNormals = true;
  }

  const int tangentAccessor = attribute(source, "TANGENT");
  bool tangentsValid = false;
  // Tangents that were given are only trusted together with the normals they were made for.
  if (tangentAccessor != -2 && normalsValid) {
    const std::vector<float> tangents = readFloatAccessor(ctx, tangentAccessor, 4, where + " TANGENT");
    if (tangents.size() / 4 != vertexCount) ctx.fail(where + ": TANGENT count differs from POSITION count");
    tangentsValid = allUnitLength(tangents, 4);
    if (tangentsValid) {
      for (size_t i = 0; i < vertexCount; ++i) {
        const glm::vec3 t =
            glm::normalize(glm::vec3(tangents[4 * i], tangents[4 * i + 1], tangents[4 * i + 2]));
        primitive.vertices[i].tangent = glm::vec4(t, tangents[4 * i + 3] < 0.0f ? -1.0f : 1.0f);
      }
    } else {
      ctx.warn(where + ": TANGENT has non-unit or non-finite vectors, tangents regenerated");
    }
  }
  if (!tangentsValid && hasUvs) {
    generateTangents(primitive.vertices, primitive.indices);
    primitive.generatedTangents = true;
  }
  return primitive;
}

}  // namespace wb::scene
