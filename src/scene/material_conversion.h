// glTF materials, textures, samplers and images -> Scene (gpu::Material layout, RGBA8 images).
#pragma once

#include "scene/load_context.h"
#include "scene/scene.h"

namespace wb::scene {

// Fills scene.images, samplers, textures, textureIsSrgb, materials and materialNames (one per glTF material,
// same indices). Unsupported material features become warnings; dangling indices throw SceneError.
void convertMaterialsAndTextures(LoadContext& ctx, Scene& scene);

// The glTF default material (all factors at their defaults: white, metallic 1, roughness 1).
gpu::Material defaultMaterial();

}  // namespace wb::scene
