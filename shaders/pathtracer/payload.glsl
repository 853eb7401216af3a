// What closest-hit and the miss shaders hand back to raygen, which owns the path loop.
#ifndef WB_PT_PAYLOAD_GLSL
#define WB_PT_PAYLOAD_GLSL

#define PAYLOAD_MISS 0u       // the ray escaped; radiance holds the (MIS-weighted) environment
#define PAYLOAD_CONTINUE 1u   // a surface was hit and a continuation ray was sampled
#define PAYLOAD_ABSORBED 2u   // a surface was hit and the path ends there (no valid continuation)

struct PathPayload {
  vec3 radiance;   // out: light reaching the previous vertex through this ray, not yet times throughput
  uint status;     // out: PAYLOAD_*
  vec3 weight;     // out: f * cos / pdf of the continuation ray
  float pdf;       // in: BRDF pdf of the ray being traced (0 for camera rays); out: pdf of the continuation
  vec3 origin;     // out: continuation ray origin (offset off the surface)
  uint bounce;     // in: index of the vertex being shaded (0 = first hit)
  vec3 direction;  // out: continuation ray direction
  float hitT;      // out: distance along the ray (for the depth view)
  vec3 albedo;     // out at bounce 0: base colour (AOV)
  uint shadowRays; // in/out: shadow rays traced along the path so far
  vec3 normal;     // out at bounce 0: shading normal (AOV)
  float pad;
  vec3 geoNormal;  // out at bounce 0: geometric normal, facing the ray (AOV)
  float pad2;
#ifdef WB_PAYLOAD_PAD_VEC4  // payload-size experiments: --define WB_PAYLOAD_PAD_VEC4=N adds N unused vec4s
  vec4 experimentPad[WB_PAYLOAD_PAD_VEC4];
#endif
};

struct ShadowPayload {
  uint visible;  // set to 1 by the shadow miss shader
};

#endif
