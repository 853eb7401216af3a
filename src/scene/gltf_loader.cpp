// loadGltf: parse (gltf_file), validate (accessor_reader, node_traversal), convert (material_conversion,
// primitive_conversion), then place the camera.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "scene/accessor_reader.h"
#include "scene/gltf_file.h"
#include "scene/load_context.h"
#include "scene/material_conversion.h"
#include "scene/node_traversal.h"
#include "scene/primitive_conversion.h"
#include "scene/scene.h"

namespace wb::scene {
namespace {

const std::set<std::string> kSupportedExtensions = {
    "KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_lights_punctual",
    "KHR_mesh_quantization",  // integer attributes are read through the generic accessor path
};
// Without these the geometry itself cannot be read.
const std::set<std::string> kGeometryExtensions = {"KHR_draco_mesh_compression", "EXT_meshopt_compression"};

void checkExtensions(LoadContext& ctx) {
  const tinygltf::Model& model = ctx.model();
  for (const std::string& extension : model.extensionsRequired) {
    if (kGeometryExtensions.count(extension)) {
      ctx.fail("required extension " + extension + " is not supported (compressed geometry)");
    }
  }
  for (const std::string& extension : model.extensionsUsed) {
    if (kSupportedExtensions.count(extension)) continue;
    const bool required = std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(),
                                    extension) != model.extensionsRequired.end();
    ctx.warn("extension " + extension + (required ? " (required)" : "") + " unsupported, ignored");
  }
}

void convertMeshes(LoadContext& ctx, Scene& scene) {
  const tinygltf::Model& model = ctx.model();
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const tinygltf::Mesh& source = model.meshes[m];
    Mesh mesh;
    mesh.name = source.name;
    for (size_t p = 0; p < source.primitives.size(); ++p) {
      const std::string where = "mesh " + std::to_string(m) +
                                (source.name.empty() ? "" : " '" + source.name + "'") + " primitive " +
                                std::to_string(p);
      if (auto primitive = convertPrimitive(ctx, source.primitives[p], where)) {
        mesh.primitives.push_back(std::move(*primitive));
      }
    }
    scene.meshes.push_back(std::move(mesh));
  }
}

void assignDefaultMaterial(Scene& scene) {
  int defaultIndex = -1;
  for (Mesh& mesh : scene.meshes) {
    for (Primitive& primitive : mesh.primitives) {
      if (primitive.material >= 0) continue;
      if (defaultIndex < 0) {
        defaultIndex = static_cast<int>(scene.materials.size());
        scene.materials.push_back(defaultMaterial());
        scene.materialNames.push_back("default");
      }
      primitive.material = defaultIndex;
    }
  }
}

Bounds computeBounds(const Scene& scene) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  bool any = false;
  for (const Instance& instance : scene.instances) {
    for (const Primitive& primitive : scene.meshes[static_cast<size_t>(instance.mesh)].primitives) {
      if (primitive.vertices.empty()) continue;
      glm::vec3 localLo(std::numeric_limits<float>::max()), localHi(-std::numeric_limits<float>::max());
      for (const gpu::Vertex& vertex : primitive.vertices) {
        localLo = glm::min(localLo, vertex.position);
        localHi = glm::max(localHi, vertex.position);
      }
      for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? localHi.x : localLo.x, (corner & 2) ? localHi.y : localLo.y,
                          (corner & 4) ? localHi.z : localLo.z);
        const glm::vec3 world = glm::vec3(instance.transform * glm::vec4(p, 1.0f));
        lo = glm::min(lo, world);
        hi = glm::max(hi, world);
        any = true;
      }
    }
  }
  return any ? Bounds{lo, hi} : Bounds{};
}

Camera cameraFromFile(const LoadContext& ctx, const CameraPlacement& placement, const Bounds& bounds) {
  const tinygltf::PerspectiveCamera& p =
      ctx.model().cameras[static_cast<size_t>(placement.camera)].perspective;
  Camera camera;
  camera.eye = glm::vec3(placement.world[3]);
  glm::vec3 forward = glm::vec3(placement.world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  glm::vec3 up = glm::vec3(placement.world * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
  if (!(glm::length(forward) > 1e-12f) || !(glm::length(up) > 1e-12f)) {
    ctx.fail("camera " + std::to_string(placement.camera) + " has a degenerate node transform");
  }
  forward = glm::normalize(forward);
  camera.up = glm::normalize(up);
  // Aim at the depth of the scene's centre (for orbiting), at least one unit ahead.
  const float depth = glm::dot(0.5f * (bounds.min + bounds.max) - camera.eye, forward);
  camera.target = camera.eye + forward * (std::isfinite(depth) && depth > 1.0f ? depth : 1.0f);
  camera.yfov = std::isfinite(p.yfov) && p.yfov > 0.0 ? static_cast<float>(p.yfov) : 0.7f;
  camera.aspect =
      std::isfinite(p.aspectRatio) && p.aspectRatio > 0.0 ? static_cast<float>(p.aspectRatio) : 0.0f;
  camera.znear = std::isfinite(p.znear) && p.znear > 0.0 ? static_cast<float>(p.znear) : 0.01f;
  camera.zfar = std::isfinite(p.zfar) && p.zfar > camera.znear ? static_cast<float>(p.zfar) : 0.0f;
  camera.fromFile = true;
  return camera;
}

}  // namespace

Scene loadGltf(const std::filesystem::path& path) {
  Scene scene;
  scene.sourcePath = path;
  const tinygltf::Model model = parseGltfFile(path, scene.warnings);
  LoadContext ctx(model, path.filename().string(), scene.warnings);
  try {
    checkExtensions(ctx);
    scene.extensionsUsed = model.extensionsUsed;
    validateBufferViewsAndAccessors(ctx);
    convertMaterialsAndTextures(ctx, scene);
    convertMeshes(ctx, scene);
    assignDefaultMaterial(scene);
    validateNodeGraph(ctx);
    const std::optional<CameraPlacement> placement = flattenNodes(ctx, scene);
    if (!model.skins.empty()) ctx.warn(std::to_string(model.skins.size()) + " skin(s) unsupported, ignored");
    if (!model.animations.empty()) {
      ctx.warn(std::to_string(model.animations.size()) + " animation(s) unsupported, ignored");
    }
    scene.bounds = computeBounds(scene);
    scene.camera =
        placement ? cameraFromFile(ctx, *placement, scene.bounds) : frameBounds(scene.bounds, 0.7f);
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {  // e.g. bad_alloc on absurd sizes: still one line naming the file
    ctx.fail(std::string("unexpected error: ") + e.what());
  }
  return scene;
}

}  // namespace wb::scene
