// Resources and helpers shared by EVERY hybrid program: the G-buffer raster stages, the shadow/AO and reflection
// ray tracing stages and the composite. Editing this file rebuilds raster and ray tracing pipelines alike.
#ifndef WB_HYBRID_COMMON_GLSL
#define WB_HYBRID_COMMON_GLSL

#extension GL_EXT_nonuniform_qualifier : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_buffer_reference_uvec2 : require
#extension GL_GOOGLE_include_directive : require

#include "../shared/gpu_types.h"
#include "../shared/sampling_math.h"

layout(set = 0, binding = WB_BIND_HYBRID_FRAME, scalar) uniform HybridFrameBlock { HybridUniforms frame; };
layout(set = 0, binding = WB_BIND_GEOMETRIES, scalar) readonly buffer GeometryBlock { GeometryInfo geometries[]; };
layout(set = 0, binding = WB_BIND_MATERIALS, scalar) readonly buffer MaterialBlock { Material materials[]; };
layout(set = 0, binding = WB_BIND_TEXTURES) uniform sampler2D textures[];
layout(set = 0, binding = WB_BIND_ENV_MAP) uniform sampler2D envMap;

layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer VertexBuffer { Vertex v[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer IndexBuffer { uint i[]; };

// The vertex at position `corner` (0 .. 3 * triangleCount - 1) of a geometry's triangle list.
Vertex fetchVertex(GeometryInfo g, uint corner) {
  IndexBuffer ib = IndexBuffer(uvec2(g.indexAddressLo, g.indexAddressHi));
  VertexBuffer vb = VertexBuffer(uvec2(g.vertexAddressLo, g.vertexAddressHi));
  return vb.v[ib.i[corner]];
}

// Textures are sampled at the base level everywhere (the scene's samplers have maxLod 0).
vec4 sampleSceneTexture(int index, vec2 uv) { return textureLod(textures[nonuniformEXT(index)], uv, 0.0); }

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
  HybridSurface s;
  vec4 base = m.baseColorFactor;
  if (m.baseColorTexture >= 0) base *= sampleSceneTexture(m.baseColorTexture, uv);
  s.baseColor = base.rgb;
  s.alpha = base.a;
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  if (m.metallicRoughnessTexture >= 0) {
    const vec4 mr = sampleSceneTexture(m.metallicRoughnessTexture, uv);
    s.roughness *= mr.g;
    s.metallic *= mr.b;
  }
  s.metallic = clamp(s.metallic, 0.0, 1.0);
  s.roughness = clamp(s.roughness, 0.0, 1.0);
  s.emissive = m.emissive;
  if (m.emissiveTexture >= 0) s.emissive *= sampleSceneTexture(m.emissiveTexture, uv).rgb;
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
  if (frame.envMapPresent != 0u) {
    return textureLod(envMap, directionToEquirect(dir, frame.envRotation), 0.0).rgb * frame.envIntensity;
  }
  return frame.ambient;
}

#endif
