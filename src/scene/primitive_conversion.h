// Turns one glTF mesh primitive into an indexed triangle list of gpu::Vertex, validating every index and
// position and generating normals/tangents where missing or unusable.
#pragma once

#include <optional>
#include <string>

#include "scene/load_context.h"
#include "scene/scene.h"

namespace wb::scene {

// Returns nothing (after a warning naming the reason) for primitives that are skipped: non-triangle modes,
// no POSITION. Throws SceneError for broken data: out-of-range indices, non-finite positions, bad accessors.
// The returned material index is the glTF one (-1 when absent), already range-checked.
std::optional<Primitive> convertPrimitive(LoadContext& ctx, const tinygltf::Primitive& primitive,
                                          const std::string& where);

}  // namespace wb::scene
