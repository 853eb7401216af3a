// Scene access for every renderer's shaders (GLSL only): the scene's bindings (geometries, materials,
// textures, environment map), vertices pulled through buffer device addresses, triangle attributes at a hit,
// textures sampled, and the rules every renderer shares: the alpha test and the environment's radiance. The
// renderers' common files include it; a renderer that specialises per scene defines WB_HAS_TEXTURES /
// WB_HAS_EMISSIVE first (0: compiled out).
#ifndef WB_SHARED_SCENE_GLSL
#define WB_SHARED_SCENE_GLSL

#extension GL_EXT_nonuniform_qualifier : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference2 : require
#extension GL_EXT_buffer_reference_uvec2 : require

#include "bindings.h"
#include "scene_types.h"
#include "sampling_math.h"

#ifndef WB_HAS_TEXTURES
#define WB_HAS_TEXTURES 1
#endif
#ifndef WB_HAS_EMISSIVE
#define WB_HAS_EMISSIVE 1
#endif

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

// A triangle's attributes at barycentrics (b1, b2), in object space.
struct TriangleHit {
  vec3 position;
  vec3 geoNormal;  // from the triangle's winding (not normalised)
  vec3 normal;     // interpolated (zero when the mesh had degenerate normals)
  vec4 tangent;
  vec2 uv;
  vec3 p0, p1, p2;  // the vertex positions (an emitter's solid-angle pdf needs the whole triangle)
};

TriangleHit fetchTriangle(GeometryInfo g, uint primitive, vec2 bary2) {
  const Vertex v0 = fetchVertex(g, 3u * primitive + 0u);
  const Vertex v1 = fetchVertex(g, 3u * primitive + 1u);
  const Vertex v2 = fetchVertex(g, 3u * primitive + 2u);
  const vec3 b = vec3(1.0 - bary2.x - bary2.y, bary2.x, bary2.y);
  TriangleHit h;
  h.position = b.x * v0.position + b.y * v1.position + b.z * v2.position;
  h.geoNormal = cross(v1.position - v0.position, v2.position - v0.position);
  h.normal = b.x * v0.normal + b.y * v1.normal + b.z * v2.normal;
  h.tangent = b.x * v0.tangent + b.y * v1.tangent + b.z * v2.tangent;
  h.uv = b.x * vec2(v0.u, v0.v) + b.y * vec2(v1.u, v1.v) + b.z * vec2(v2.u, v2.v);
  h.p0 = v0.position;
  h.p1 = v1.position;
  h.p2 = v2.position;
  return h;
}

// Textures are sampled at the base level everywhere (ray tracing stages have no derivatives; the scene's
// samplers have maxLod 0). Without textures in the scene the binding is not even referenced (white).
#if WB_HAS_TEXTURES
vec4 sampleTexture(int index, vec2 uv) { return textureLod(textures[nonuniformEXT(index)], uv, 0.0); }
#else
vec4 sampleTexture(int index, vec2 uv) { return vec4(1.0); }
#endif

// A material's inputs with its textures applied at uv (glTF metallic-roughness: roughness in G, metallic in
// B). Metallic and roughness are not clamped here.
struct MaterialInputs {
  vec4 baseColor;  // rgb colour, a alpha
  float metallic;
  float roughness;
  vec3 emissive;  // zero where WB_HAS_EMISSIVE is 0
};

MaterialInputs materialInputs(Material m, vec2 uv) {
  MaterialInputs s;
  s.baseColor = m.baseColorFactor;
  if (m.baseColorTexture >= 0) s.baseColor *= sampleTexture(m.baseColorTexture, uv);
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  if (m.metallicRoughnessTexture >= 0) {
    const vec4 mr = sampleTexture(m.metallicRoughnessTexture, uv);
    s.roughness *= mr.g;
    s.metallic *= mr.b;
  }
#if WB_HAS_EMISSIVE
  s.emissive = m.emissive;
  if (m.emissiveTexture >= 0) s.emissive *= sampleTexture(m.emissiveTexture, uv).rgb;
#else
  s.emissive = vec3(0.0);
#endif
  return s;
}

// Base colour alpha (factor times texture), as alpha testing and blending see it.
float materialAlpha(Material m, vec2 uv) {
  float a = m.baseColorFactor.a;
  if (m.baseColorTexture >= 0) a *= sampleTexture(m.baseColorTexture, uv).a;
  return a;
}

// The alpha rule of every renderer: whether a hit on material m, whose base colour alpha there is `alpha`, is let
// through. OPAQUE: never; MASK: below alphaCutoff (glTF); BLEND: below blendThreshold, a uniform random number in
// [0, 1) for stochastic transparency (the path tracer: opaque with probability alpha), or WB_ALPHA_BLEND_AS_MASK
// for a renderer that is not stochastic (the hybrid modes' raster and rays).
#define WB_ALPHA_BLEND_AS_MASK 0.5
bool alphaRejected(Material m, float alpha, float blendThreshold) {
  if (m.alphaMode == WB_ALPHA_OPAQUE) return false;
  return alpha < (m.alphaMode == WB_ALPHA_MASK ? m.alphaCutoff : blendThreshold);
}

// The environment map's radiance along a direction (equirectangular, rotated about +Y, times intensity).
vec3 envMapRadiance(vec3 dir, float rotation, float intensity) {
  return textureLod(envMap, directionToEquirect(dir, rotation), 0.0).rgb * intensity;
}

// The environment's radiance along a direction, for every renderer: kind WB_ENV_MAP reads the map (rotated about
// +Y, times intensity), WB_ENV_CONSTANT is `constantRadiance` (the colour times the intensity), WB_ENV_NONE black.
vec3 environmentRadiance(int kind, vec3 dir, vec3 constantRadiance, float rotation, float intensity) {
  if (kind == WB_ENV_MAP) return envMapRadiance(dir, rotation, intensity);
  if (kind == WB_ENV_CONSTANT) return constantRadiance;
  return vec3(0.0);
}

#endif
