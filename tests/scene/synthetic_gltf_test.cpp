// Small glTF files written by the test itself: every index/attribute component type, byteStride, sparse
// accessors, broken ranges, cycles, generated normals/tangents, cameras and the supported KHR extensions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/scene.h"
#include "synthetic_gltf.h"

namespace wb::scene {
namespace {

using nlohmann::json;
using test::kByte;
using test::kFloat;
using test::kShort;
using test::kUByte;
using test::kUInt;
using test::kUShort;
using test::SyntheticGltf;

// A right triangle in the XZ plane, counter-clockwise seen from +Y.
const std::vector<float> kTrianglePositions = {0, 0, 0, 1, 0, 0, 0, 0, -1};

bool hasWarning(const Scene& scene, const std::string& needle) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

std::string refusal(const SyntheticGltf& gltf, const std::string& name) {
  const std::filesystem::path path = gltf.write(name);
  try {
    loadGltf(path);
  } catch (const SceneError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(name + ".gltf"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << name << " loaded, expected SceneError";
  return {};
}

template <class T>
void checkIndexType(int componentType, const std::string& name) {
  SyntheticGltf gltf;
  const int positions = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  const int normals = gltf.addData(std::vector<float>{0, 1, 0, 0, 1, 0, 0, 1, 0}, kFloat, "VEC3");
  const int indices = gltf.addData(std::vector<T>{2, 1, 0}, componentType, "SCALAR");
  gltf.addSingleMeshNode(
      {{"attributes", {{"POSITION", positions}, {"NORMAL", normals}}}, {"indices", indices}});
  const Scene scene = loadGltf(gltf.write(name));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].primitives[0].indices, (std::vector<uint32_t>{2, 1, 0}));
  EXPECT_EQ(scene.triangleCount(), 1u);
}

TEST(SyntheticGltf, EveryIndexComponentType) {
  checkIndexType<uint8_t>(kUByte, "indices_u8");
  checkIndexType<uint16_t>(kUShort, "indices_u16");
  checkIndexType<uint32_t>(kUInt, "indices_u32");
}

TEST(SyntheticGltf, SignedOrFloatIndicesAreRefused) {
  SyntheticGltf gltf;
  const int positions = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  const int indices = gltf.addData(std::vector<int16_t>{0, 1, 2}, kShort, "SCALAR");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", positions}}}, {"indices", indices}});
  EXPECT_NE(refusal(gltf, "indices_short").find("unsigned"), std::string::npos);
}

TEST(SyntheticGltf, NonIndexedGetsSequentialIndicesAndGeneratedNormals) {
  SyntheticGltf gltf;
  const int positions = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", positions}}}});
  const Scene scene = loadGltf(gltf.write("non_indexed"));
  const Primitive& primitive = scene.meshes[0].primitives[0];
  EXPECT_EQ(primitive.indices, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_TRUE(primitive.generatedNormals);
  EXPECT_FALSE(primitive.generatedTangents);  // no UVs: nothing to derive tangents from
  for (const gpu::Vertex& v : primitive.vertices) {
    EXPECT_NEAR(v.normal.x, 0.0f, 1e-6f);
    EXPECT_NEAR(v.normal.y, 1.0f, 1e-6f);
    EXPECT_NEAR(v.normal.z, 0.0f, 1e-6f);
    EXPECT_EQ(v.tangent, glm::vec4(0.0f));
  }
}

// UVs (0,0), (0,1), (1,0) in each encoding glTF allows for TEXCOORD_0.
void checkUvs(const Scene& scene) {
  const auto& v = scene.meshes[0].primitives[0].vertices;
  ASSERT_EQ(v.size(), 3u);
  EXPECT_FLOAT_EQ(v[0].u, 0.0f);
  EXPECT_FLOAT_EQ(v[1].v, 1.0f);
  EXPECT_FLOAT_EQ(v[2].u, 1.0f);
  EXPECT_FLOAT_EQ(v[2].v, 0.0f);
  EXPECT_TRUE(scene.meshes[0].primitives[0].generatedTangents);
  // u grows along -Z, v along +X; normal +Y: cross(+Y, -Z) = -X, opposite to +v, so handedness -1.
  EXPECT_NEAR(v[0].tangent.z, -1.0f, 1e-6f);
  EXPECT_EQ(v[0].tangent.w, -1.0f);
}

TEST(SyntheticGltf, EveryTexcoordComponentType) {
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    const int uv = gltf.addData(std::vector<float>{0, 0, 0, 1, 1, 0}, kFloat, "VEC2");
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}});
    checkUvs(loadGltf(gltf.write("uv_float")));
  }
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    const int uv = gltf.addData(std::vector<uint8_t>{0, 0, 0, 255, 255, 0, 0, 0}, kUByte, "VEC2", true);
    gltf.json["accessors"][uv]["count"] = 3;  // 2 padding bytes after the data
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}});
    checkUvs(loadGltf(gltf.write("uv_ubyte_normalized")));
  }
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    const int uv = gltf.addData(std::vector<uint16_t>{0, 0, 0, 65535, 65535, 0}, kUShort, "VEC2", true);
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}});
    checkUvs(loadGltf(gltf.write("uv_ushort_normalized")));
  }
}

TEST(SyntheticGltf, QuantizedPositionsAndNormalizedByteNormals) {
  // KHR_mesh_quantization-style data: short positions, normalized signed byte normals (-127 -> -1).
  SyntheticGltf gltf;
  gltf.json["extensionsUsed"] = {"KHR_mesh_quantization"};
  const int p = gltf.addData(std::vector<int16_t>{0, 0, 0, 0, 0, -2, 2, 0, 0, 0}, kShort, "VEC3");
  gltf.json["accessors"][p]["count"] = 3;
  const int n =
      gltf.addData(std::vector<int8_t>{0, 127, 0, 0, 0, 127, 0, 0, 0, -127, 0, 0}, kByte, "VEC4", true);
  gltf.json["accessors"][n]["type"] = "VEC3";
  gltf.json["accessors"][n]["count"] = 3;
  gltf.json["bufferViews"][gltf.json["accessors"][n]["bufferView"].get<int>()]["byteStride"] = 4;
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}});
  const Scene scene = loadGltf(gltf.write("quantized"));
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  const auto& v = scene.meshes[0].primitives[0].vertices;
  EXPECT_EQ(v[1].position, glm::vec3(0, 0, -2));
  EXPECT_EQ(v[0].normal, glm::vec3(0, 1, 0));
  EXPECT_EQ(v[2].normal, glm::vec3(0, -1, 0));
  EXPECT_FALSE(scene.meshes[0].primitives[0].generatedNormals);
}

TEST(SyntheticGltf, InterleavedByteStride) {
  // position (12 bytes) + uv (8 bytes) interleaved with a stride of 20.
  std::vector<float> interleaved = {0, 0, 0, 0.25f, 0.5f, 0, 0, -1, 0.75f, 1, 1, 0, 0, 1, 0};
  std::vector<uint8_t> bytes(interleaved.size() * 4);
  std::memcpy(bytes.data(), interleaved.data(), bytes.size());
  SyntheticGltf gltf;
  const int view = gltf.addBufferView(bytes, 20);
  const int p = gltf.addAccessor(view, kFloat, 3, "VEC3");
  const int uv = gltf.addAccessor(view, kFloat, 3, "VEC2", false, 12);
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}, {"TEXCOORD_0", uv}}}});
  const Scene scene = loadGltf(gltf.write("stride"));
  const auto& v = scene.meshes[0].primitives[0].vertices;
  EXPECT_EQ(v[1].position, glm::vec3(0, 0, -1));
  EXPECT_EQ(v[2].position, glm::vec3(1, 0, 0));
  EXPECT_FLOAT_EQ(v[1].u, 0.75f);
  EXPECT_FLOAT_EQ(v[2].v, 0.0f);
  EXPECT_FLOAT_EQ(v[0].v, 0.5f);

  // The same view with a stride smaller than one element is refused.
  gltf.json["bufferViews"][view]["byteStride"] = 8;
  EXPECT_NE(refusal(gltf, "stride_too_small").find("byteStride"), std::string::npos);
}

TEST(SyntheticGltf, SparseAccessorSubstitutesValues) {
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  const int sparseIndices = gltf.addBufferView({1, 0});  // u16 index 1
  std::vector<uint8_t> value(12);
  const float replacement[3] = {5, 6, 7};
  std::memcpy(value.data(), replacement, 12);
  const int sparseValues = gltf.addBufferView(value);
  gltf.json["accessors"][p]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", sparseIndices}, {"componentType", kUShort}}},
      {"values", {{"bufferView", sparseValues}}}};
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
  const Scene scene = loadGltf(gltf.write("sparse"));
  EXPECT_EQ(scene.meshes[0].primitives[0].vertices[1].position, glm::vec3(5, 6, 7));
  EXPECT_EQ(scene.meshes[0].primitives[0].vertices[2].position, glm::vec3(0, 0, -1));

  gltf.json["accessors"][p]["sparse"]["count"] = 2;  // needs 4 index bytes, the view has 2
  EXPECT_NE(refusal(gltf, "sparse_overflow").find("sparse"), std::string::npos);
}

TEST(SyntheticGltf, OutOfRangeIndexIsRefused) {
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  const int i = gltf.addData(std::vector<uint16_t>{0, 1, 3}, kUShort, "SCALAR");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}, {"indices", i}});
  EXPECT_NE(refusal(gltf, "index_out_of_range").find("index 3"), std::string::npos);
}

TEST(SyntheticGltf, NanAndInfinitePositionsAreRefused) {
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    std::vector<float> positions = kTrianglePositions;
    positions[4] = bad;
    SyntheticGltf gltf;
    const int p = gltf.addData(positions, kFloat, "VEC3");
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
    EXPECT_NE(refusal(gltf, "nan_position").find("NaN or infinite"), std::string::npos);
  }
}

TEST(SyntheticGltf, RangesOutsideBuffersAreRefused) {
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    gltf.json["accessors"][p]["count"] = 4;  // one element past the bufferView
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
    EXPECT_NE(refusal(gltf, "accessor_past_view").find("bufferView 0 has 36"), std::string::npos);
  }
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    gltf.json["accessors"][p]["byteOffset"] = 4;
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
    EXPECT_NE(refusal(gltf, "accessor_offset").find("need 40 bytes"), std::string::npos);
  }
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    gltf.json["bufferViews"][0]["byteOffset"] = 8;  // 8 + 36 > 36-byte buffer
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
    EXPECT_NE(refusal(gltf, "view_past_buffer").find("outside buffer 0"), std::string::npos);
  }
  {
    SyntheticGltf gltf;
    const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
    gltf.json["accessors"][p]["count"] = 4000000000u;  // overflow attempt
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
    refusal(gltf, "huge_count");
  }
  {
    SyntheticGltf gltf;
    gltf.addData(kTrianglePositions, kFloat, "VEC3");
    gltf.addSingleMeshNode({{"attributes", {{"POSITION", 7}}}});
    EXPECT_NE(refusal(gltf, "missing_accessor").find("accessor 7"), std::string::npos);
  }
}

TEST(SyntheticGltf, CyclesAreRefused) {
  SyntheticGltf gltf;
  gltf.json["scenes"] = {{{"nodes", {0}}}};
  gltf.json["nodes"] = {{{"children", {1}}}, {{"children", {2}}}, {{"children", {1}}}};
  EXPECT_NE(refusal(gltf, "cycle").find("cycle"), std::string::npos);
  gltf.json["nodes"] = {{{"children", {0}}}};
  EXPECT_NE(refusal(gltf, "self_cycle").find("cycle"), std::string::npos);
  gltf.json["nodes"] = {{{"children", {5}}}};
  EXPECT_NE(refusal(gltf, "bad_child").find("child 5"), std::string::npos);
}

// glTF: without NORMAL the normals are flat. A quad folded along its diagonal keeps two face normals.
TEST(SyntheticGltf, MissingNormalsAreFlat) {
  SyntheticGltf gltf;
  const int p = gltf.addData(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 0, -1, 1, 1, -1}, kFloat, "VEC3");
  const int i = gltf.addData(std::vector<uint16_t>{0, 1, 2, 2, 1, 3}, kUShort, "SCALAR");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}, {"indices", i}});
  const Scene scene = loadGltf(gltf.write("flat"));
  const Primitive& prim = scene.meshes[0].primitives[0];
  EXPECT_TRUE(prim.generatedNormals);
  ASSERT_EQ(prim.vertices.size(), 6u);  // the shared corners are split
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(prim.vertices[v].normal.y, 1.0f, 1e-6f);
  const glm::vec3 second = glm::normalize(glm::cross(glm::vec3(1, 0, 1), glm::vec3(1, 1, 0)));
  for (int v = 3; v < 6; ++v) EXPECT_NEAR(glm::dot(prim.vertices[v].normal, second), 1.0f, 1e-5f);
}

TEST(SyntheticGltf, PrimitiveModes) {
  SyntheticGltf gltf;
  const int p = gltf.addData(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, kFloat, "VEC3");
  const int n = gltf.addData(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, kFloat, "VEC3");
  const json attributes = {{"POSITION", p}, {"NORMAL", n}};  // with normals: no flat-normal split
  gltf.addSingleMeshNode({{"attributes", attributes}, {"mode", 5}});
  gltf.json["meshes"][0]["primitives"].push_back({{"attributes", attributes}, {"mode", 1}});
  gltf.json["meshes"][0]["primitives"].push_back({{"attributes", attributes}, {"mode", 6}});
  const Scene scene = loadGltf(gltf.write("modes"));
  ASSERT_EQ(scene.meshes[0].primitives.size(), 2u);  // strip and fan kept, lines skipped
  EXPECT_EQ(scene.meshes[0].primitives[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(scene.meshes[0].primitives[1].indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_TRUE(hasWarning(scene, "LINES"));
}

TEST(SyntheticGltf, NodeTransformsMatrixAndTrs) {
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
  // Parent: translate (1,2,3), rotate 90 degrees about Y, scale 2. Child: matrix translating by (1,0,0).
  const float h = std::sqrt(0.5f);
  gltf.json["nodes"] = {
      {{"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}, {"scale", {2, 2, 2}}, {"children", {1}}},
      {{"mesh", 0}, {"name", "child"}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1}}}};
  const Scene scene = loadGltf(gltf.write("transforms"));
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].nodeName, "child");
  // (1,0,0) scaled by 2 -> (2,0,0), rotated 90 degrees about Y -> (0,0,-2), translated -> (1,2,1).
  const glm::vec3 origin = glm::vec3(scene.instances[0].transform * glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(origin.x, 1.0f, 1e-5f);
  EXPECT_NEAR(origin.y, 2.0f, 1e-5f);
  EXPECT_NEAR(origin.z, 1.0f, 1e-5f);
}

TEST(SyntheticGltf, CameraImportAndAutomaticFraming) {
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}});
  {
    const Scene scene = loadGltf(gltf.write("no_camera"));
    EXPECT_FALSE(scene.camera.fromFile);
    const Camera expected = frameBounds(scene.bounds, 0.7f);
    EXPECT_EQ(scene.camera.eye, expected.eye);
    // Bounds (0,0,-1)..(1,0,0): centre (0.5, 0, -0.5), radius sqrt(2)/2. The triangle lies flat in XZ (seen
    // along -Z it would be a line): the camera looks down -Y at it from above, -Z up in the image.
    EXPECT_EQ(scene.camera.target, glm::vec3(0.5f, 0.0f, -0.5f));
    const float radius = std::sqrt(2.0f) / 2.0f;
    EXPECT_NEAR(scene.camera.eye.y - scene.camera.target.y, 1.1f * radius / std::sin(0.35f), 1e-5f);
    EXPECT_FLOAT_EQ(scene.camera.eye.x, scene.camera.target.x);
    EXPECT_FLOAT_EQ(scene.camera.eye.z, scene.camera.target.z);
    EXPECT_EQ(scene.camera.up, glm::vec3(0.0f, 0.0f, -1.0f));
    EXPECT_GT(scene.camera.zfar, scene.camera.eye.y + 1.0f);
  }
  // A camera node rotated 90 degrees about Y (looking along -X) at (5, 1, 0), under a translated parent.
  const float h = std::sqrt(0.5f);
  gltf.json["cameras"] = {
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}, {"aspectRatio", 1.5}}}}};
  gltf.json["nodes"].push_back({{"translation", {4, 0, 0}}, {"children", {2}}});
  gltf.json["nodes"].push_back({{"camera", 0}, {"translation", {1, 1, 0}}, {"rotation", {0, h, 0, h}}});
  gltf.json["scenes"][0]["nodes"].push_back(1);
  const Scene scene = loadGltf(gltf.write("camera"));
  ASSERT_TRUE(scene.camera.fromFile);
  EXPECT_NEAR(glm::length(scene.camera.eye - glm::vec3(5, 1, 0)), 0.0f, 1e-5f);
  const glm::vec3 forward = glm::normalize(scene.camera.target - scene.camera.eye);
  EXPECT_NEAR(forward.x, -1.0f, 1e-5f);
  EXPECT_NEAR(scene.camera.up.y, 1.0f, 1e-5f);
  EXPECT_FLOAT_EQ(scene.camera.yfov, 0.5f);
  EXPECT_FLOAT_EQ(scene.camera.aspect, 1.5f);
  EXPECT_EQ(scene.camera.zfar, 0.0f);  // infinite
}

TEST(SyntheticGltf, MaterialsAndKhrExtensions) {
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}, {"material", 0}});
  gltf.json["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_specular",
                                 "KHR_lights_punctual", "KHR_materials_clearcoat"};
  gltf.json["materials"] = {
      {{"name", "glow"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.1, 0.2, 0.3, 0.4}}, {"metallicFactor", 0.25}, {"roughnessFactor", 0.75}}},
       {"emissiveFactor", {1.0, 0.5, 0.25}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.3},
       {"doubleSided", true},
       {"extensions",
        {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}},
         {"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {0.9, 0.8, 0.7}}}},
         {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}}}};
  const float h = std::sqrt(0.5f);
  gltf.json["extensions"] = {
      {"KHR_lights_punctual",
       {{"lights",
         {{{"type", "directional"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 2.0}},
          {{"type", "point"}, {"name", "bulb"}, {"intensity", 10.0}},
          {{"type", "spot"}, {"intensity", 10.0}, {"spot", {{"outerConeAngle", 0.5}}}}}}}}};
  // Directional light rotated -90 degrees about X: its -Z points down (-Y).
  gltf.json["nodes"].push_back(
      {{"rotation", {-h, 0, 0, h}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  gltf.json["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
  gltf.json["nodes"].push_back({{"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
  gltf.json["scenes"][0]["nodes"] = {0, 1, 2, 3};
  const Scene scene = loadGltf(gltf.write("khr_extensions"));
  ASSERT_EQ(scene.materials.size(), 1u);
  const gpu::Material& m = scene.materials[0];
  EXPECT_EQ(scene.materialNames[0], "glow");
  EXPECT_FLOAT_EQ(m.baseColorFactor.w, 0.4f);
  EXPECT_FLOAT_EQ(m.metallic, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness, 0.75f);
  EXPECT_EQ(m.emissive, glm::vec3(4.0f, 2.0f, 1.0f));
  EXPECT_FLOAT_EQ(m.specularFactor, 0.5f);
  EXPECT_NEAR(m.specularColorFactor.z, 0.7f, 1e-6f);
  EXPECT_EQ(m.alphaMode, WB_ALPHA_MASK);
  EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
  EXPECT_EQ(m.flags, WB_MATERIAL_DOUBLE_SIDED);
  EXPECT_EQ(m.baseColorTexture, -1);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_NEAR(scene.lights[0].direction.y, -1.0f, 1e-6f);
  EXPECT_NEAR(glm::length(scene.lights[0].direction), 1.0f, 1e-6f);
  EXPECT_EQ(scene.lights[0].radiance, glm::vec3(2.0f, 1.0f, 0.5f));
  EXPECT_EQ(scene.lights[0].cosAngularRadius, 1.0f);
  EXPECT_TRUE(hasWarning(scene, "point light 1 'bulb'"));
  EXPECT_TRUE(hasWarning(scene, "spot light"));
  EXPECT_TRUE(hasWarning(scene, "extension KHR_materials_clearcoat"));
  EXPECT_FALSE(hasWarning(scene, "KHR_materials_specular"));
}

TEST(SyntheticGltf, TexturesSamplersAndUnsupportedTextureFeatures) {
  // A 1x1 PNG (opaque red), embedded as a data URI.
  const std::vector<uint8_t> png = {0x89, 0x50, 0x4E, 0x47, 0x0D, 0x0A, 0x1A, 0x0A, 0x00, 0x00, 0x00, 0x0D,
                                    0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01,
                                    0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xDE, 0x00, 0x00, 0x00,
                                    0x0C, 0x49, 0x44, 0x41, 0x54, 0x08, 0xD7, 0x63, 0xF8, 0xCF, 0xC0, 0x00,
                                    0x00, 0x03, 0x01, 0x01, 0x00, 0x18, 0xDD, 0x8D, 0xB0, 0x00, 0x00, 0x00,
                                    0x00, 0x49, 0x45, 0x4E, 0x44, 0xAE, 0x42, 0x60, 0x82};
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}, {"material", 0}});
  gltf.json["images"] = {{{"uri", "data:image/png;base64," + test::base64(png)}}};
  gltf.json["samplers"] = {{{"magFilter", 9728}}};
  gltf.json["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 0}}};
  gltf.json["materials"] = {
      {{"pbrMetallicRoughness",
        {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}},
         {"metallicRoughnessTexture", {{"index", 1}}}}},
       {"normalTexture", {{"index", 1}, {"scale", 0.5}}},
       {"emissiveTexture",
        {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"scale", {2, 2}}}}}}}}}};
  const Scene scene = loadGltf(gltf.write("textures"));
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].width, 1);
  ASSERT_EQ(scene.images[0].rgba8.size(), 4u);
  EXPECT_EQ(scene.images[0].rgba8[0], 255);
  EXPECT_EQ(scene.images[0].rgba8[1], 0);
  EXPECT_EQ(scene.images[0].rgba8[3], 255);
  EXPECT_EQ(scene.samplers[0].magFilter, 9728);
  EXPECT_EQ(scene.samplers[0].minFilter, 9987);  // default when absent
  EXPECT_EQ(scene.samplers[0].wrapT, 10497);
  EXPECT_EQ(scene.textures[1].sampler, -1);
  EXPECT_EQ(scene.textureIsSrgb, (std::vector<bool>{true, false}));
  const gpu::Material& m = scene.materials[0];
  EXPECT_EQ(m.baseColorTexture, 0);
  EXPECT_EQ(m.metallicRoughnessTexture, 1);
  EXPECT_EQ(m.normalTexture, 1);
  EXPECT_FLOAT_EQ(m.normalScale, 0.5f);
  EXPECT_EQ(m.emissiveTexture, 0);
  EXPECT_TRUE(hasWarning(scene, "texCoord 1"));
  EXPECT_TRUE(hasWarning(scene, "KHR_texture_transform"));

  gltf.json["materials"][0]["normalTexture"]["index"] = 9;
  EXPECT_NE(refusal(gltf, "bad_texture").find("texture 9"), std::string::npos);
}

// A texture whose image does not exist (nvpro's cornellBox.gltf has one, used by no material) costs that
// texture alone, with a warning; a material using it keeps its factors.
TEST(SyntheticGltf, TextureWithoutItsImageIsAWarning) {
  SyntheticGltf gltf;
  const int p = gltf.addData(kTrianglePositions, kFloat, "VEC3");
  gltf.addSingleMeshNode({{"attributes", {{"POSITION", p}}}, {"material", 0}});
  gltf.json["textures"] = {{{"source", 0}, {"name", "tex"}}, {{"source", 3}}};
  gltf.json["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 1}}}}}}};
  const Scene scene = loadGltf(gltf.write("texture_without_image"));
  ASSERT_EQ(scene.textures.size(), 2u);
  EXPECT_EQ(scene.textures[0].image, -1);
  EXPECT_TRUE(hasWarning(scene, "texture 0 refers to image 0, which does not exist"));
  EXPECT_TRUE(hasWarning(scene, "texture 1 refers to image 3, which does not exist"));
  EXPECT_EQ(scene.materials[0].baseColorTexture, -1);
}

// Automatic framing looks down -Z unless the model is flat seen that way: then along its thinnest axis.
TEST(SyntheticGltf, AutomaticFramingOfFlatModels) {
  Bounds wall{{0.0f, -1.0f, -2.0f}, {0.0f, 1.0f, 2.0f}};  // a wall in YZ
  Camera c = frameBounds(wall, 0.7f);
  EXPECT_GT(c.eye.x - c.target.x, 1.0f);
  EXPECT_FLOAT_EQ(c.eye.y, c.target.y);
  EXPECT_EQ(c.up, glm::vec3(0.0f, 1.0f, 0.0f));
  Bounds slab{{-5.0f, 0.0f, -5.0f}, {5.0f, 0.1f, 5.0f}};  // a ground slab: 1% as thick as it is wide
  c = frameBounds(slab, 0.7f);
  EXPECT_GT(c.eye.y - c.target.y, 1.0f);
  Bounds box{{-1.0f, -1.0f, -0.3f}, {1.0f, 1.0f, 0.3f}};  // some depth: the -Z view as before
  c = frameBounds(box, 0.7f);
  EXPECT_GT(c.eye.z - c.target.z, 1.0f);
  EXPECT_FLOAT_EQ(c.eye.x, c.target.x);
  EXPECT_FLOAT_EQ(c.eye.y, c.target.y);
}

TEST(SyntheticGltf, CompressedGeometryExtensionsAreRefused) {
  SyntheticGltf gltf;
  gltf.json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  gltf.json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_NE(refusal(gltf, "draco").find("KHR_draco_mesh_compression"), std::string::npos);
}

TEST(SyntheticGltf, MissingPositionSkipsPrimitiveWithWarning) {
  SyntheticGltf gltf;
  const int uv = gltf.addData(std::vector<float>{0, 0, 0, 1, 1, 0}, kFloat, "VEC2");
  gltf.addSingleMeshNode({{"attributes", {{"TEXCOORD_0", uv}}}});
  const Scene scene = loadGltf(gltf.write("no_position"));
  EXPECT_TRUE(scene.meshes[0].primitives.empty());
  EXPECT_TRUE(hasWarning(scene, "POSITION"));
  EXPECT_EQ(scene.triangleCount(), 0u);
}

}  // namespace
}  // namespace wb::scene

// `--sun-angle` is the lights' angular diameter in degrees, in every mode; DirectionalLight::cosAngularRadius
// is the cosine of half of it. 0 makes delta lights (cosine exactly 1), a negative angle keeps each light's
// own.
TEST(SceneLights, SunAngleIsTheAngularDiameter) {
  EXPECT_EQ(wb::scene::sunCosAngularRadius(0.9f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(wb::scene::sunCosAngularRadius(1.0f, 0.53f), std::cos(glm::radians(0.265f)));
  EXPECT_FLOAT_EQ(wb::scene::sunCosAngularRadius(1.0f, 90.0f), std::sqrt(0.5f));
  EXPECT_EQ(wb::scene::sunCosAngularRadius(0.99f, -1.0f), 0.99f);
  std::vector<wb::gpu::DirectionalLight> lights(2);
  lights[0].cosAngularRadius = 1.0f;
  lights[1].cosAngularRadius = 0.9f;
  const auto sized = wb::scene::withSunAngle(lights, 10.0f);
  EXPECT_FLOAT_EQ(sized[0].cosAngularRadius, std::cos(glm::radians(5.0f)));
  EXPECT_FLOAT_EQ(sized[1].cosAngularRadius, std::cos(glm::radians(5.0f)));
  const auto kept = wb::scene::withSunAngle(lights, -1.0f);
  EXPECT_EQ(kept[0].cosAngularRadius, 1.0f);
  EXPECT_EQ(kept[1].cosAngularRadius, 0.9f);
}
