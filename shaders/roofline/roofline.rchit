#version 460
#extension GL_GOOGLE_include_directive : require
// The hit: distance and geometric normal (world space, facing the ray) from the triangle's three vertices.
#include "common.glsl"

layout(location = 0) rayPayloadInEXT RooflinePayload payload;

void main() {
  const GeometryInfo g = geometries[gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT];
  const vec3 p0 = fetchVertex(g, 3u * gl_PrimitiveID + 0u).position;
  const vec3 p1 = fetchVertex(g, 3u * gl_PrimitiveID + 1u).position;
  const vec3 p2 = fetchVertex(g, 3u * gl_PrimitiveID + 2u).position;
  vec3 n = normalize((cross(p1 - p0, p2 - p0) * gl_WorldToObjectEXT).xyz);
  if (any(isnan(n))) n = -gl_WorldRayDirectionEXT;  // a zero-area triangle: face the ray
  payload.normal = dot(n, gl_WorldRayDirectionEXT) > 0.0 ? -n : n;
  payload.hitT = gl_HitTEXT;
}
