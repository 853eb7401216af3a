// Resources and helpers shared by EVERY hybrid program: the G-buffer raster stages, the shadow/AO and reflection
// ray tracing stages and the composite. Editing this file rebuilds raster and ray tracing pipelines alike.
#ifndef WB_HYBRID_COMMON_GLSL
#define WB_HYBRID_COMMON_GLSL

#extension GL_GOOGLE_include_directive : require

// Geometries, materials, textures, the environment map; vertex fetch, material inputs (shared with the path
// tracer).
#include "../shared/scene.glsl"
#include "../shared/hybrid_types.h"
#include "../shared/sun.h"

layout(set = 0, binding = WB_BIND_HYBRID_FRAME, scalar) uniform HybridFrameBlock { HybridUniforms frame; };

// A material with its textures applied at uv (normal maps are not used by the hybrid modes).
struct HybridSurface {
  vec3 baseColor;
  float alpha;
  vec3 emissive;
  float metallic;
  float roughness;
  float specularFactor;
};

HybridSurface evalSurface(Material m, vec2 uv) {
  const MaterialInputs inputs = materialInputs(m, uv);
  HybridSurface s;
  s.baseColor = inputs.baseColor.rgb;
  s.alpha = inputs.baseColor.a;
  s.metallic = clamp(inputs.metallic, 0.0, 1.0);
  s.roughness = clamp(inputs.roughness, 0.0, 1.0);
  s.emissive = inputs.emissive;
  s.specularFactor = m.specularFactor;
  return s;
}

// The alpha test (shared/scene.glsl's rule): MASK below its cutoff; BLEND as a mask at 0.5 (the hybrid modes are
// not stochastic).
bool alphaRejected(Material m, float alpha) { return alphaRejected(m, alpha, WB_ALPHA_BLEND_AS_MASK); }

// The environment's radiance along a direction (shared/scene.glsl): the map, or the constant colour.
vec3 envRadiance(vec3 dir) {
  return environmentRadiance(frame.envMapPresent != 0u ? WB_ENV_MAP : WB_ENV_CONSTANT, dir, frame.ambient,
                             frame.envRotation, frame.envIntensity);
}

#endif
