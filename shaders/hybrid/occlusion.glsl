// Occlusion rays traced from a raygen: the payload and the visibility query (any-hit still runs for alpha).
#ifndef WB_HYBRID_OCCLUSION_GLSL
#define WB_HYBRID_OCCLUSION_GLSL

layout(location = OCCLUSION_PAYLOAD_LOCATION) rayPayloadEXT uint occlusionVisible;

// True when nothing blocks origin + t * dir for t < tmax. `missIndex` picks the ray type's miss shader.
bool traceVisible(vec3 origin, vec3 dir, float tmax, uint missIndex) {
  occlusionVisible = 0u;
  traceRayEXT(tlas, gl_RayFlagsTerminateOnFirstHitEXT | gl_RayFlagsSkipClosestHitShaderEXT, 0xFF, 0, 0, missIndex,
              origin, 0.0, dir, tmax, OCCLUSION_PAYLOAD_LOCATION);
  return occlusionVisible != 0u;
}

#endif
