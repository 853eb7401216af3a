// What closest-hit and the miss shaders hand back to raygen, which owns the path loop.
#ifndef WB_PT_PAYLOAD_GLSL
#define WB_PT_PAYLOAD_GLSL

#define PAYLOAD_MISS 0u       // the ray escaped; radiance holds the (MIS-weighted) environment
#define PAYLOAD_CONTINUE 1u   // a surface was hit and a continuation ray was sampled
#define PAYLOAD_ABSORBED 2u   // a surface was hit and the path ends there (no valid continuation)
#define PAYLOAD_UNOCCLUDED 3u // a shadow ray reached its light (set by the shadow miss shader)

// Next-event estimation: closest-hit computes each light sample's contribution and hands raygen the shadow ray
// that decides it. Raygen traces path and shadow rays from one traceRayEXT call site: lavapipe compiles a whole
// traversal into the code per call site (a second one in closest-hit lengthens the pipeline's JIT, which every
// shader edit waits for), and the pipeline needs no recursion.
struct ShadowRequest {
  vec3 direction;  // from PathPayload.origin
  float tMax;
  vec3 radiance;   // contribution if unoccluded (f * Le * MIS weight / pdf), not yet times the path throughput
  float pad;
};
// One light sample per directional light plus one of the environment or the area lights. The generic build
// reads the light count at run time and holds up to WB_GENERIC_MAX_LIGHTS (the host raises it for scenes with
// more directional lights).
#if defined(WB_SPECIALIZED)
#define WB_SHADOW_REQUESTS (WB_LIGHT_COUNT + 1u)
#else
#define WB_SHADOW_REQUESTS (WB_GENERIC_MAX_LIGHTS + 1u)
#endif

struct PathPayload {
  vec3 radiance;   // out: light reaching the previous vertex through this ray, not yet times throughput
  uint status;     // out: PAYLOAD_*
  vec3 weight;     // out: f * cos / pdf of the continuation ray
  float pdf;       // in: BRDF pdf of the ray being traced (0 for camera rays); out: pdf of the continuation
  vec3 origin;     // out: continuation and shadow ray origin (offset off the surface)
  uint bounce;     // in: index of the vertex being shaded (0 = first hit)
  vec3 direction;  // out: continuation ray direction
  float hitT;      // out: distance along the ray (for the depth view)
  vec3 albedo;     // out at bounce 0: base colour (AOV)
  uint shadowRequestCount; // out: valid entries of shadowRequests
  vec3 normal;     // out at bounce 0: shading normal (AOV)
#if WB_TIMED
  uint shadeClocks;  // out: the clocks closest-hit or the environment miss shader spent (the cost variants)
#else
  float pad;
#endif
  vec3 geoNormal;  // out at bounce 0: geometric normal, facing the ray (AOV)
#if WB_COST_ISOLATE
  uint launchPixel;  // in: the pixel's index within the launch (WB_PIXEL in common.glsl)
#else
  float pad2;
#endif
  ShadowRequest shadowRequests[WB_SHADOW_REQUESTS];  // out: NEE shadow rays, all leaving from origin
#ifdef WB_PAYLOAD_PAD_VEC4  // payload-size experiments: --define WB_PAYLOAD_PAD_VEC4=N adds N unused vec4s
  vec4 experimentPad[WB_PAYLOAD_PAD_VEC4];
#endif
};

#endif
