// Resources and helpers shared by EVERY hybrid program: the G-buffer raster stages, the shadow/AO and reflection
// ray tracing stages and the composite. Editing this file rebuilds raster and ray tracing pipelines alike.
#ifndef WB_HYBRID_COMMON_GLSL
#define WB_HYBRID_COMMON_GLSL

#extension GL_GOOGLE_include_directive : require

// Geometries, materials, textures, the environment map; vertex fetch, material inputs (shared with the path
// tracer).
#include "../shared/scene.glsl"

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

// Alpha test: MASK below its cutoff; BLEND is treated as a mask at 0.5 (the hybrid modes are not stochastic).
bool alphaRejected(Material m, float alpha) {
  if (m.alphaMode == WB_ALPHA_OPAQUE) return false;
  return alpha < (m.alphaMode == WB_ALPHA_MASK ? m.alphaCutoff : 0.5);
}

// Environment radiance along a direction (the constant colour when there is no map).
vec3 envLookup(vec3 dir) {
  if (frame.envMapPresent != 0u) return envMapRadiance(dir, frame.envRotation, frame.envIntensity);
  return frame.ambient;
}

#endif
