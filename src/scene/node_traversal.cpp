#include "scene/node_traversal.h"

#include <cmath>
#include <utility>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace wb::scene {
namespace {

constexpr size_t kMaxNodeVisits = size_t{1} << 22;

std::string nodeLabel(const tinygltf::Model& model, size_t index) {
  const std::string& name = model.nodes[index].name;
  return "node " + std::to_string(index) + (name.empty() ? std::string() : " '" + name + "'");
}

bool allFinite(const std::vector<double>& values) {
  for (double value : values) {
    if (!std::isfinite(value)) return false;
  }
  return true;
}

std::vector<int> rootNodes(LoadContext& ctx) {
  const tinygltf::Model& model = ctx.model();
  if (model.scenes.empty()) {
    std::vector<bool> isChild(model.nodes.size(), false);
    for (const tinygltf::Node& node : model.nodes) {
      for (int child : node.children) isChild[static_cast<size_t>(child)] = true;
    }
    std::vector<int> roots;
    for (size_t i = 0; i < model.nodes.size(); ++i) {
      if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    if (!roots.empty()) ctx.warn("file has no scenes; all root nodes are shown");
    return roots;
  }
  int sceneIndex = model.defaultScene;
  if (sceneIndex < 0) sceneIndex = 0;
  if (static_cast<size_t>(sceneIndex) >= model.scenes.size()) {
    ctx.fail("default scene " + std::to_string(sceneIndex) + " does not exist");
  }
  if (model.scenes.size() > 1)
    ctx.warn("file has several scenes; only scene " + std::to_string(sceneIndex) + " is shown");
  return model.scenes[static_cast<size_t>(sceneIndex)].nodes;
}

void addLight(LoadContext& ctx, Scene& scene, const tinygltf::Node& node, const std::string& label,
              const glm::mat4& world) {
  const auto it = node.extensions.find("KHR_lights_punctual");
  if (it == node.extensions.end()) return;
  const tinygltf::Value& value = it->second;
  if (!value.IsObject() || !value.Has("light") || !value.Get("light").IsNumber()) {
    ctx.fail(label + ": KHR_lights_punctual without a light index");
  }
  const int lightIndex = value.Get("light").GetNumberAsInt();
  const auto& lights = ctx.model().lights;
  if (lightIndex < 0 || static_cast<size_t>(lightIndex) >= lights.size()) {
    ctx.fail(label + " refers to light " + std::to_string(lightIndex) + ", which does not exist");
  }
  const tinygltf::Light& light = lights[static_cast<size_t>(lightIndex)];
  const std::string lightLabel = "KHR_lights_punctual " + light.type + " light " +
                                 std::to_string(lightIndex) +
                                 (light.name.empty() ? std::string() : " '" + light.name + "'");
  if (light.type != "directional") {
    ctx.warn(lightLabel + " unsupported (only directional lights), ignored");
    return;
  }
  glm::vec3 color(1.0f);
  if (light.color.size() == 3) color = glm::vec3(light.color[0], light.color[1], light.color[2]);
  const glm::vec3 direction = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
  const float length = glm::length(direction);
  if (!(length > 1e-12f) || !std::isfinite(length) || !std::isfinite(light.intensity)) {
    ctx.fail(lightLabel + " has a degenerate direction or intensity");
  }
  gpu::DirectionalLight out{};
  out.direction = direction / length;
  out.cosAngularRadius = 1.0f;
  out.radiance = color * static_cast<float>(light.intensity);
  scene.lights.push_back(out);
}

}  // namespace

glm::mat4 localTransform(const LoadContext& ctx, const tinygltf::Node& node, size_t nodeIndex) {
  const std::string label = nodeLabel(ctx.model(), nodeIndex);
  if (!allFinite(node.matrix) || !allFinite(node.translation) || !allFinite(node.rotation) ||
      !allFinite(node.scale)) {
    ctx.fail(label + " has a non-finite transform");
  }
  if (node.matrix.size() == 16) {
    glm::dmat4 m;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(c * 4 + r)];
    }
    return glm::mat4(m);
  }
  glm::mat4 t(1.0f), r(1.0f), s(1.0f);
  if (node.translation.size() == 3) {
    t[3] = glm::vec4(node.translation[0], node.translation[1], node.translation[2], 1.0f);
  }
  if (node.rotation.size() == 4) {
    glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // w, x, y, z
    const double length = glm::length(q);
    if (length > 1e-12) r = glm::mat4(glm::mat4_cast(q / length));
  }
  if (node.scale.size() == 3) {
    s[0][0] = static_cast<float>(node.scale[0]);
    s[1][1] = static_cast<float>(node.scale[1]);
    s[2][2] = static_cast<float>(node.scale[2]);
  }
  return t * r * s;
}

void validateNodeGraph(const LoadContext& ctx) {
  const tinygltf::Model& model = ctx.model();
  const size_t count = model.nodes.size();
  for (size_t i = 0; i < count; ++i) {
    for (int child : model.nodes[i].children) {
      if (child < 0 || static_cast<size_t>(child) >= count) {
        ctx.fail(nodeLabel(model, i) + " has child " + std::to_string(child) + ", which does not exist");
      }
    }
  }
  for (size_t s = 0; s < model.scenes.size(); ++s) {
    for (int root : model.scenes[s].nodes) {
      if (root < 0 || static_cast<size_t>(root) >= count) {
        ctx.fail("scene " + std::to_string(s) + " refers to node " + std::to_string(root) +
                 ", which does not exist");
      }
    }
  }
  // Iterative three-colour depth-first search over the whole graph (no recursion: chains may be deep).
  enum : uint8_t { kWhite, kGrey, kBlack };
  std::vector<uint8_t> colour(count, kWhite);
  std::vector<std::pair<size_t, size_t>> stack;  // node, next child position
  for (size_t start = 0; start < count; ++start) {
    if (colour[start] != kWhite) continue;
    stack.push_back({start, 0});
    colour[start] = kGrey;
    while (!stack.empty()) {
      auto& [node, next] = stack.back();
      const std::vector<int>& children = model.nodes[node].children;
      if (next < children.size()) {
        const size_t child = static_cast<size_t>(children[next++]);
        if (colour[child] == kGrey) {
          ctx.fail("node graph has a cycle: " + nodeLabel(model, node) + " has ancestor " +
                   nodeLabel(model, child) + " as child");
        }
        if (colour[child] == kWhite) {
          colour[child] = kGrey;
          stack.push_back({child, 0});
        }
      } else {
        colour[node] = kBlack;
        stack.pop_back();
      }
    }
  }
}

std::optional<CameraPlacement> flattenNodes(LoadContext& ctx, Scene& scene) {
  const tinygltf::Model& model = ctx.model();
  std::optional<CameraPlacement> camera;
  std::vector<std::pair<size_t, glm::mat4>> stack;
  const std::vector<int> roots = rootNodes(ctx);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it)
    stack.push_back({static_cast<size_t>(*it), glm::mat4(1.0f)});
  size_t visits = 0;
  while (!stack.empty()) {
    const auto [index, parent] = stack.back();
    stack.pop_back();
    if (++visits > kMaxNodeVisits) ctx.fail("node graph expands to more than 4M node instances");
    const tinygltf::Node& node = model.nodes[index];
    const std::string label = nodeLabel(model, index);
    const glm::mat4 world = parent * localTransform(ctx, node, index);
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model.meshes.size()) {
        ctx.fail(label + " refers to mesh " + std::to_string(node.mesh) + ", which does not exist");
      }
      scene.instances.push_back(Instance{node.mesh, world, node.name});
    }
    if (node.skin >= 0) ctx.warn(label + ": skin ignored (meshes shown in bind pose)");
    if (!node.weights.empty()) ctx.warn(label + ": morph target weights ignored");
    if (node.camera >= 0) {
      if (static_cast<size_t>(node.camera) >= model.cameras.size()) {
        ctx.fail(label + " refers to camera " + std::to_string(node.camera) + ", which does not exist");
      }
      const tinygltf::Camera& source = model.cameras[static_cast<size_t>(node.camera)];
      if (source.type == "perspective") {
        if (!camera) camera = CameraPlacement{node.camera, world};
      } else {
        ctx.warn("camera " + std::to_string(node.camera) + " ('" + source.name + "'): " + source.type +
                 " projection unsupported, ignored");
      }
    }
    addLight(ctx, scene, node, label, world);
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
      stack.push_back({static_cast<size_t>(*child), world});
    }
  }
  return camera;
}

}  // namespace wb::scene
