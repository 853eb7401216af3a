// What the reflection closest-hit hands back to the reflection raygen (which owns the bounce loop).
#ifndef WB_HYBRID_REFLECT_PAYLOAD_GLSL
#define WB_HYBRID_REFLECT_PAYLOAD_GLSL

#define REFLECTION_PAYLOAD_LOCATION 0

struct ReflectionPayload {
  vec3 position;  // world space hit point
  uint hit;       // 0 = miss
  vec3 normal;    // shading normal facing the ray's origin
  float metallic;
  vec3 geoNormal;  // geometric normal facing the ray's origin
  float roughness;
  vec3 baseColor;
  float specularFactor;
  vec3 emissive;
  float pad0;
};

#endif
