// Ray tracing side of the hybrid modes: the scene TLAS, the G-buffer read back as a world position and normal,
// occlusion rays (terminate on first hit, no closest-hit) and random numbers (shared/random.h's hash stream).
#ifndef WB_HYBRID_RT_COMMON_GLSL
#define WB_HYBRID_RT_COMMON_GLSL

#extension GL_EXT_ray_tracing : require
#include "common.glsl"
#define WB_RANDOM_NO_TABLES
#include "../shared/random.h"

layout(set = 0, binding = WB_BIND_TLAS) uniform accelerationStructureEXT tlas;

#define OCCLUSION_PAYLOAD_LOCATION 1

#endif
