#version 460
#extension GL_GOOGLE_include_directive : require
// Reflection hits: surface data only (no rays traced here; the raygen loops and shades).
#include "rt_common.glsl"
#include "reflect_payload.glsl"

layout(location = REFLECTION_PAYLOAD_LOCATION) rayPayloadInEXT ReflectionPayload payload;
hitAttributeEXT vec2 attribs;

void main() {
  const GeometryInfo g = geometries[gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT];
  const Material m = materials[g.materialIndex];
  const TriangleHit h = fetchTriangle(g, gl_PrimitiveID, attribs);
  const HybridSurface s = evalSurface(m, h.uv);
  const vec3 wo = -gl_WorldRayDirectionEXT;
  vec3 ng = normalize((h.geoNormal * gl_WorldToObjectEXT).xyz);
  if (any(isnan(ng))) ng = wo;
  const bool frontFace = dot(ng, wo) >= 0.0;
  if (!frontFace) ng = -ng;
  vec3 ns = (h.normal * gl_WorldToObjectEXT).xyz;
  ns = dot(ns, ns) > 1e-20 ? normalize(ns) : ng;
  if (dot(ns, wo) < 0.0) ns = -ns;
  payload.position = gl_ObjectToWorldEXT * vec4(h.position, 1.0);
  payload.hit = 1u;
  payload.normal = ns;
  payload.geoNormal = ng;
  payload.metallic = s.metallic;
  payload.roughness = s.roughness;
  payload.baseColor = s.baseColor;
  payload.specularFactor = s.specularFactor;
  payload.emissive = frontFace || (m.flags & WB_MATERIAL_DOUBLE_SIDED) != 0u ? s.emissive : vec3(0.0);
}
