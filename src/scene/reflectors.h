// The scene's glossy reflectors: instances with a smooth metal or smooth specular surface, as world-space
// bounding spheres. The path tracer sends part of the continuation rays of diffuse surfaces towards them
// (shaders/pathtracer/guiding.glsl; `--define WB_REFLECTOR_GUIDING=0` turns it off): the sun reflected by a
// smooth sphere onto the ground (a caustic) is a small, bright target that cosine sampling meets rarely.
#pragma once
#include <vector>

#include "scene/scene.h"

namespace wb::scene {

// At most this many reflectors (the shaders loop over them at every path vertex); the largest are kept.
inline constexpr size_t kMaxReflectors = 8;

// Whether a material reflects light sharply enough to focus a light onto other surfaces: roughness at most
// 0.5 and metallic at least 0.5, or a specular layer (specularFactor > 0) of roughness at most 0.3 (factors
// only; textures are not looked at).
bool isGlossyReflector(const gpu::Material& m);
// The bounding sphere (xyz centre, w radius) of every instance with a glossy primitive, the largest
// kMaxReflectors by radius, with the scene's materials or live-edited ones (same indices).
std::vector<glm::vec4> glossyReflectors(const Scene& scene, const std::vector<gpu::Material>& materials);

}  // namespace wb::scene
