// Ray tracing side of the hybrid modes: the scene TLAS, the G-buffer read back as a world position and normal,
// occlusion rays (terminate on first hit, no closest-hit) and a small hash random generator.
#ifndef WB_HYBRID_RT_COMMON_GLSL
#define WB_HYBRID_RT_COMMON_GLSL

#extension GL_EXT_ray_tracing : require
#include "common.glsl"

layout(set = 0, binding = WB_BIND_TLAS) uniform accelerationStructureEXT tlas;

#define OCCLUSION_PAYLOAD_LOCATION 1

uint hybridHash(uint v) {
  const uint state = v * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float hybridRandom(inout uint state) {
  state = hybridHash(state);
  return float(state >> 8) * (1.0 / 16777216.0);
}

// Object-space triangle data of the current hit.
struct HybridHit {
  vec3 position;   // object space
  vec3 geoNormal;  // object space, from the winding (not normalised)
  vec3 normal;     // object space, interpolated
  vec2 uv;
};

HybridHit fetchHybridHit(GeometryInfo g, uint primitive, vec2 bary2) {
  const Vertex v0 = fetchVertex(g, 3u * primitive + 0u);
  const Vertex v1 = fetchVertex(g, 3u * primitive + 1u);
  const Vertex v2 = fetchVertex(g, 3u * primitive + 2u);
  const vec3 b = vec3(1.0 - bary2.x - bary2.y, bary2.x, bary2.y);
  HybridHit h;
  h.position = b.x * v0.position + b.y * v1.position + b.z * v2.position;
  h.geoNormal = cross(v1.position - v0.position, v2.position - v0.position);
  h.normal = b.x * v0.normal + b.y * v1.normal + b.z * v2.normal;
  h.uv = b.x * vec2(v0.u, v0.v) + b.y * vec2(v1.u, v1.v) + b.z * vec2(v2.u, v2.v);
  return h;
}

#endif
