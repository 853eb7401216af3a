// The renderer-facing description of a loaded scene: meshes as interleaved gpu::Vertex arrays, flattened node
// instances, materials in the shader's layout, decoded RGBA8 images, directional lights and a camera.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared/scene_types.h"

namespace wb::scene {

// Thrown for any file that cannot be loaded; what() is one line and names the file.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Decoded image, always RGBA8 (4 bytes per pixel, row 0 at the top). Empty (width 0) when the source could
// not be decoded (e.g. a WebP or KTX2 image); materials never reference textures whose image is empty.
struct Image {
  std::string name;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba8;
};

// glTF sampler enum values (9728 NEAREST, 9729 LINEAR, 9984..9987 mipmap modes; 10497 REPEAT, 33071 CLAMP,
// 33648 MIRRORED). Absent values get LINEAR / LINEAR_MIPMAP_LINEAR / REPEAT.
struct Sampler {
  int magFilter = 9729, minFilter = 9987, wrapS = 10497, wrapT = 10497;
};

struct Texture {
  int image = -1;    // index into Scene::images; -1 when the texture has no usable image
  int sampler = -1;  // index into Scene::samplers; -1 = default Sampler{}
};

struct Primitive {
  std::vector<gpu::Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list, every index < vertices.size()
  int material = -1;              // index into Scene::materials (always valid after loading)
  bool generatedNormals = false, generatedTangents = false;
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

// One placement of a mesh: the world transform of the node that references it.
struct Instance {
  int mesh = -1;
  glm::mat4 transform{1.0f};
  std::string nodeName;
};

struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 1.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
  float yfov = 0.7f;    // vertical field of view, radians
  float aspect = 0.0f;  // 0 = unspecified (use the viewport's)
  float znear = 0.01f;
  float zfar = 0.0f;  // 0 = infinite (as in glTF)
  bool fromFile = false;
};

struct Bounds {
  glm::vec3 min{0.0f}, max{0.0f};  // world space, over all instances; all zero for an empty scene
};

struct Scene {
  std::filesystem::path sourcePath;
  std::vector<Mesh> meshes;  // one per glTF mesh, same indices
  std::vector<Instance> instances;
  // A default material (glTF defaults, named "default") is appended when any primitive has none.
  std::vector<gpu::Material> materials;
  std::vector<std::string> materialNames;
  std::vector<Texture> textures;    // one per glTF texture, same indices
  std::vector<Image> images;        // one per glTF image, same indices
  std::vector<Sampler> samplers;    // one per glTF sampler, same indices
  std::vector<bool> textureIsSrgb;  // per texture: true if used as baseColor or emissive
  // Directional lights; glTF's are delta lights (cosAngularRadius 1) until `--sun-angle` gives them a size
  // (withSunAngle).
  std::vector<gpu::DirectionalLight> lights;
  Camera camera;  // the first perspective camera of the default scene, else frameBounds(bounds, 0.7)
  Bounds bounds;
  std::vector<std::string> warnings;  // one line per unsupported feature met, each named
  std::vector<std::string>
      extensionsUsed;  // the file's glTF extensions (extensionsUsed), for the feature set

  size_t triangleCount() const;  // over all instances (a mesh placed twice counts twice)
};

// The sun's size, the same in every mode: `--sun-angle` is the angular diameter in degrees (0: a delta
// light); DirectionalLight::cosAngularRadius is the cosine of half of it. A negative angle keeps the light's
// own size.
float sunCosAngularRadius(float lightCosAngularRadius, float sunAngleDeg);
// The lights as the renderers shade them: each with sunCosAngularRadius applied.
std::vector<gpu::DirectionalLight> withSunAngle(std::vector<gpu::DirectionalLight> lights, float sunAngleDeg);

// Loads a .gltf (external or data-URI buffers) or .glb file. Throws SceneError with a one-line reason.
Scene loadGltf(const std::filesystem::path& path);

// A camera looking at the centre of the bounds, far enough back to see all of them: along -Z, or, for a model
// that is flat seen that way (its XY projection under 5% of its largest face), along its thinnest axis (from
// above for a ground plane in XZ).
Camera frameBounds(const Bounds& bounds, float yfov);

}  // namespace wb::scene
