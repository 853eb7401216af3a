// Ray tracing side of the hybrid modes: the scene TLAS, the G-buffer read back as a world position and normal,
// occlusion rays (terminate on first hit, no closest-hit) and a small hash random generator.
#ifndef WB_HYBRID_RT_COMMON_GLSL
#define WB_HYBRID_RT_COMMON_GLSL

#extension GL_EXT_ray_tracing : require
#include "common.glsl"
#include "../shared/hash.h"

layout(set = 0, binding = WB_BIND_TLAS) uniform accelerationStructureEXT tlas;

#define OCCLUSION_PAYLOAD_LOCATION 1

float hybridRandom(inout uint state) {
  state = pcgHash(state);
  return float(state >> 8) * (1.0 / 16777216.0);
}

#endif
