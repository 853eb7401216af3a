// Imports every model under ../shared/assets/gltf and checks counts, transforms and materials read from the
// files.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/paths.h"
#include "scene/scene.h"

namespace wb::scene {
namespace {

std::filesystem::path gltfDir() {
  return wb::sharedDir() / "assets" / "gltf";
}

bool hasWarning(const Scene& scene, const std::string& needle) {
  return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                     [&](const std::string& w) { return w.find(needle) != std::string::npos; });
}

size_t primitiveCount(const Scene& scene) {
  size_t count = 0;
  for (const Mesh& mesh : scene.meshes) count += mesh.primitives.size();
  return count;
}

const Instance* findInstance(const Scene& scene, const std::string& name) {
  for (const Instance& instance : scene.instances) {
    if (instance.nodeName == name) return &instance;
  }
  return nullptr;
}

void expectVec(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(SharedAssets, BoxEmbedded) {
  const Scene scene = loadGltf(gltfDir() / "Box/glTF-Embedded/Box.gltf");
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(primitiveCount(scene), 1u);
  EXPECT_EQ(scene.triangleCount(), 12u);
  ASSERT_EQ(scene.instances.size(), 1u);
  // Node 0's matrix (a -90 degree rotation about X) applies to child node 1, which holds the mesh.
  const glm::mat4& m = scene.instances[0].transform;
  EXPECT_FLOAT_EQ(m[1][2], -1.0f);
  EXPECT_FLOAT_EQ(m[2][1], 1.0f);
  EXPECT_FLOAT_EQ(m[0][0], 1.0f);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materialNames[0], "Red");
  EXPECT_NEAR(scene.materials[0].baseColorFactor.r, 0.8f, 1e-6f);
  EXPECT_EQ(scene.materials[0].baseColorFactor.g, 0.0f);
  EXPECT_EQ(scene.materials[0].metallic, 0.0f);
  EXPECT_EQ(scene.materials[0].roughness, 1.0f);
  EXPECT_EQ(scene.materials[0].specularFactor, 1.0f);
  EXPECT_EQ(scene.meshes[0].primitives[0].vertices.size(), 24u);
  EXPECT_FALSE(scene.meshes[0].primitives[0].generatedNormals);
  EXPECT_FALSE(scene.camera.fromFile);
  // Box spans [-0.5, 0.5]^3.
  expectVec(scene.bounds.min, glm::vec3(-0.5f));
  expectVec(scene.bounds.max, glm::vec3(0.5f));
}

TEST(SharedAssets, SimpleMeshesSharesOneMeshAndGetsDefaultMaterial) {
  const Scene scene = loadGltf(gltfDir() / "SimpleMeshes/glTF-Embedded/SimpleMeshes.gltf");
  EXPECT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.triangleCount(), 2u);
  EXPECT_EQ(scene.instances[0].mesh, 0);
  EXPECT_EQ(scene.instances[1].mesh, 0);
  expectVec(glm::vec3(scene.instances[1].transform[3]), glm::vec3(1.0f, 0.0f, 0.0f));
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materialNames[0], "default");
  EXPECT_EQ(scene.meshes[0].primitives[0].material, 0);
  EXPECT_EQ(scene.materials[0].metallic, 1.0f);  // glTF default material
}

TEST(SharedAssets, CamerasUsesFirstPerspectiveAndWarnsOrthographic) {
  const Scene scene = loadGltf(gltfDir() / "assimp/cameras/Cameras.gltf");
  EXPECT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.triangleCount(), 2u);
  ASSERT_TRUE(scene.camera.fromFile);
  expectVec(scene.camera.eye, glm::vec3(0.5f, 0.5f, 3.0f));
  const glm::vec3 forward = glm::normalize(scene.camera.target - scene.camera.eye);
  expectVec(forward, glm::vec3(0.0f, 0.0f, -1.0f));
  expectVec(scene.camera.up, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_FLOAT_EQ(scene.camera.yfov, 0.7f);
  EXPECT_FLOAT_EQ(scene.camera.aspect, 1.0f);
  EXPECT_FLOAT_EQ(scene.camera.znear, 0.01f);
  EXPECT_FLOAT_EQ(scene.camera.zfar, 100.0f);
  EXPECT_TRUE(hasWarning(scene, "orthographic"));
  // Node 0 is rotated by the quaternion (-0.383, 0, 0, 0.92375).
  const glm::mat4& m = scene.instances[0].transform;
  EXPECT_NEAR(m[1][1], 1.0f - 2.0f * 0.383f * 0.383f, 1e-3f);
}

void checkBoxTextured(const Scene& scene, int wrapS) {
  EXPECT_EQ(scene.triangleCount(), 12u);
  ASSERT_EQ(scene.textures.size(), 1u);
  ASSERT_EQ(scene.images.size(), 1u);
  EXPECT_EQ(scene.images[0].width, 211);
  EXPECT_EQ(scene.images[0].height, 211);
  EXPECT_EQ(scene.images[0].rgba8.size(), 211u * 211u * 4u);
  EXPECT_EQ(scene.textures[0].image, 0);
  EXPECT_EQ(scene.textures[0].sampler, 0);
  ASSERT_EQ(scene.samplers.size(), 1u);
  EXPECT_EQ(scene.samplers[0].magFilter, 9729);
  EXPECT_EQ(scene.samplers[0].minFilter, 9986);
  EXPECT_EQ(scene.samplers[0].wrapS, wrapS);
  EXPECT_TRUE(scene.textureIsSrgb[0]);
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
  EXPECT_EQ(scene.materials[0].normalTexture, -1);
  EXPECT_TRUE(scene.meshes[0].primitives[0].generatedTangents);  // UVs but no TANGENT
  for (const gpu::Vertex& v : scene.meshes[0].primitives[0].vertices) {
    EXPECT_NEAR(glm::length(glm::vec3(v.tangent)), 1.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(glm::vec3(v.tangent), v.normal), 0.0f, 1e-4f);
  }
}

TEST(SharedAssets, BoxTexturedGltfAndGlb) {
  checkBoxTextured(loadGltf(gltfDir() / "assimp/BoxTextured-glTF/BoxTextured.gltf"), 33648);
  checkBoxTextured(loadGltf(gltfDir() / "assimp/BoxTextured-glTF-Binary/BoxTextured.glb"), 10497);
}

TEST(SharedAssets, LightsPunctualLampWarnsPointLightsAndWebp) {
  const Scene scene = loadGltf(gltfDir() / "LightsPunctualLamp/LightsPunctualLamp.glb");
  EXPECT_EQ(scene.meshes.size(), 3u);
  EXPECT_EQ(scene.instances.size(), 3u);
  EXPECT_EQ(scene.triangleCount(), 4070u + 14u + 1916u);
  EXPECT_TRUE(scene.lights.empty());  // five point lights, none directional
  EXPECT_TRUE(hasWarning(scene, "point light"));
  EXPECT_TRUE(hasWarning(scene, "EXT_texture_webp"));
  EXPECT_TRUE(hasWarning(scene, "KHR_materials_transmission"));
  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_EQ(scene.materials[1].alphaMode, WB_ALPHA_BLEND);
  EXPECT_EQ(scene.materials[0].flags & WB_MATERIAL_DOUBLE_SIDED, WB_MATERIAL_DOUBLE_SIDED);
  EXPECT_NEAR(scene.materials[1].roughness, 0.5f, 1e-6f);
  // WebP-only textures cannot be decoded: materials fall back to factors.
  for (const gpu::Material& material : scene.materials) EXPECT_EQ(material.baseColorTexture, -1);
  EXPECT_FALSE(scene.meshes[0].primitives[0].generatedTangents);  // the file has TANGENT
}

TEST(SharedAssets, DamagedHelmet) {
  const Scene scene = loadGltf(gltfDir() / "DamagedHelmet/DamagedHelmet.gltf");
  EXPECT_EQ(scene.triangleCount(), 15452u);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].nodeName, "node_damagedHelmet_-6514");
  // Rotation of +90 degrees about X: local +Y goes to +Z.
  expectVec(glm::vec3(scene.instances[0].transform[1]), glm::vec3(0.0f, 0.0f, 1.0f));
  ASSERT_EQ(scene.materials.size(), 1u);
  const gpu::Material& material = scene.materials[0];
  EXPECT_EQ(material.baseColorTexture, 0);
  EXPECT_EQ(material.metallicRoughnessTexture, 1);
  EXPECT_EQ(material.emissiveTexture, 2);
  EXPECT_EQ(material.normalTexture, 4);
  expectVec(material.emissive, glm::vec3(1.0f));
  EXPECT_EQ(scene.textureIsSrgb, (std::vector<bool>{true, false, true, false, false}));
  ASSERT_EQ(scene.images.size(), 5u);
  EXPECT_EQ(scene.images[0].width, 2048);  // Default_albedo.jpg
  EXPECT_EQ(scene.images[0].height, 2048);
  for (const Image& image : scene.images) {
    EXPECT_GT(image.width, 0);
    EXPECT_EQ(image.rgba8.size(), size_t(image.width) * size_t(image.height) * 4u);
  }
  EXPECT_TRUE(hasWarning(scene, "occlusionTexture"));
  EXPECT_TRUE(scene.meshes[0].primitives[0].generatedTangents);
  EXPECT_EQ(scene.samplers[0].wrapS, 10497);
  EXPECT_EQ(scene.samplers[0].minFilter, 9987);
}

TEST(SharedAssets, TinygltfCubesAndUrisWithSpaces) {
  const Scene cube = loadGltf(gltfDir() / "tinygltf/Cube/Cube.gltf");
  EXPECT_EQ(cube.triangleCount(), 12u);
  EXPECT_FALSE(cube.meshes[0].primitives[0].generatedTangents);
  EXPECT_EQ(cube.images.size(), 2u);
  EXPECT_EQ(cube.materials[0].metallicRoughnessTexture, 1);
  for (const char* file : {"CubeImageUriSpaces.gltf", "CubeImageUriMultipleSpaces.gltf"}) {
    const Scene scene = loadGltf(gltfDir() / "tinygltf/CubeImageUriSpaces" / file);
    EXPECT_EQ(scene.triangleCount(), 12u) << file;  // unsigned byte indices
    ASSERT_EQ(scene.images.size(), 1u) << file;
    EXPECT_EQ(scene.images[0].width, 2) << file;
    EXPECT_EQ(scene.materials[0].baseColorTexture, 0) << file;
  }
}

TEST(SharedAssets, TextureTransformIsNamedInWarnings) {
  const Scene scene = loadGltf(gltfDir() / "assimp/textureTransform/TextureTransformTest.gltf");
  EXPECT_EQ(scene.meshes.size(), 9u);
  EXPECT_EQ(scene.instances.size(), 12u);
  EXPECT_EQ(scene.triangleCount(), 24u);
  EXPECT_TRUE(hasWarning(scene, "KHR_texture_transform"));
  const Instance* child = findInstance(scene, "Rotation - Correct");
  ASSERT_NE(child, nullptr);
  expectVec(glm::vec3(child->transform[3]), glm::vec3(-1.1f - 0.07904822f, -0.55f - 0.51626749f, 0.01f));
}

TEST(SharedAssets, VulkanSamples) {
  struct Expected {
    const char* file;
    size_t triangles, instances;
  };
  for (const Expected& e :
       {Expected{"cube.gltf", 12, 1}, Expected{"geosphere.gltf", 1280, 1}, Expected{"teapot.gltf", 9128, 1},
        Expected{"textured_unit_cube.gltf", 12, 1}, Expected{"torusknot.gltf", 2880, 1},
        Expected{"primitives/primitives.gltf", 3636, 6}}) {
    const Scene scene = loadGltf(gltfDir() / "vulkan-samples" / e.file);
    EXPECT_EQ(scene.triangleCount(), e.triangles) << e.file;
    EXPECT_EQ(scene.instances.size(), e.instances) << e.file;
  }
  const Scene geosphere = loadGltf(gltfDir() / "vulkan-samples/geosphere.gltf");
  ASSERT_TRUE(geosphere.camera.fromFile);
  expectVec(geosphere.camera.eye, glm::vec3(7.481131553649902f, -6.5076398849487305f, 5.34366512298584f));
  EXPECT_NEAR(geosphere.camera.yfov, 0.50337994f, 1e-6f);
  EXPECT_EQ(geosphere.camera.aspect, 0.0f);
  const Scene primitives = loadGltf(gltfDir() / "vulkan-samples/primitives/primitives.gltf");
  const Instance* cube = findInstance(primitives, "Cube_1");
  ASSERT_NE(cube, nullptr);
  // Child of Sphere_1 (T = (0.5117, 3.5782, -0.1224), uniform S = 0.21859): world T = T_parent + S * T_child.
  const float s = 0.21859341859817505f;
  expectVec(
      glm::vec3(cube->transform[3]),
      glm::vec3(0.5117151141166687f + s * 7.071179389953613f, 3.578230142593384f + s * 1.2679672241210938f,
                -0.12235216796398163f + s * 1.1186718940734863f),
      1e-4f);
  EXPECT_NEAR(cube->transform[0][0], s * 2.0508482456207275f, 1e-5f);
}

}  // namespace
}  // namespace wb::scene
