#include "scene/scene.h"

namespace wb::scene {

size_t Scene::triangleCount() const {
  size_t count = 0;
  for (const Instance& instance : instances) {
    if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= meshes.size()) continue;
    for (const Primitive& primitive : meshes[static_cast<size_t>(instance.mesh)].primitives) {
      count += primitive.indices.size() / 3;
    }
  }
  return count;
}

}  // namespace wb::scene
