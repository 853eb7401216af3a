// Flattens the default scene's node hierarchy into world-space mesh instances, directional lights and the
// first perspective camera's placement.
#pragma once

#include <optional>

#include "scene/load_context.h"
#include "scene/scene.h"

namespace wb::scene {

struct CameraPlacement {
  int camera = -1;  // glTF camera index (perspective)
  glm::mat4 world{1.0f};
};

// Throws SceneError for dangling child/scene indices and for cycles anywhere in the node graph.
void validateNodeGraph(const LoadContext& ctx);

// Root nodes of the default scene (scene 0 when none is marked; all parentless nodes when there are no
// scenes). Appends scene.instances and scene.lights; returns the first perspective camera met in depth-first
// order.
std::optional<CameraPlacement> flattenNodes(LoadContext& ctx, Scene& scene);

// The local transform of a node (matrix, or T * R * S). Throws for non-finite values.
glm::mat4 localTransform(const LoadContext& ctx, const tinygltf::Node& node, size_t nodeIndex);

}  // namespace wb::scene
