// The G-buffer as the ray tracing and composite passes read it.
#ifndef WB_HYBRID_GBUFFER_GLSL
#define WB_HYBRID_GBUFFER_GLSL

layout(set = 0, binding = WB_BIND_GBUF_ALBEDO) uniform sampler2D gbufAlbedo;
layout(set = 0, binding = WB_BIND_GBUF_NORMAL) uniform sampler2D gbufNormal;
layout(set = 0, binding = WB_BIND_GBUF_DEPTH) uniform sampler2D gbufDepth;
layout(set = 0, binding = WB_BIND_GBUF_EMISSIVE) uniform sampler2D gbufEmissive;

// World position of the pixel centre at a (reversed-Z) depth.
vec3 gbufWorldPosition(ivec2 pixel, float depth) {
  const vec2 ndc = (vec2(pixel) + 0.5) / vec2(frame.width, frame.height) * 2.0 - 1.0;
  const vec4 w = frame.viewProjInverse * vec4(ndc, depth, 1.0);
  return w.xyz / w.w;
}

// The camera ray direction through the pixel centre.
vec3 gbufViewDirection(ivec2 pixel) { return normalize(gbufWorldPosition(pixel, 1.0) - frame.cameraPosition); }

// Origin for a secondary ray leaving a reconstructed G-buffer position: depth reconstruction is not exact, so
// the offset grows with the distance to the camera.
vec3 gbufRayOrigin(vec3 position, vec3 normal) {
  const float dist = length(position - frame.cameraPosition);
  return position + normal * (2e-4 + 2e-4 * dist);
}

#endif
