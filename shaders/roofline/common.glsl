// The bare-ray roofline's resources: the path tracer's scene (TLAS, geometries) and push constants. Its shaders
// do as little as a ray needs: the rate they reach is what traversal of this scene costs on the device.
#ifndef WB_ROOFLINE_COMMON_GLSL
#define WB_ROOFLINE_COMMON_GLSL

#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require

#define WB_HAS_TEXTURES 0
#define WB_HAS_EMISSIVE 0
#include "../shared/bindings.h"
#include "../shared/roofline_types.h"
#include "../shared/scene.glsl"

layout(set = 0, binding = WB_BIND_TLAS) uniform accelerationStructureEXT tlas;
layout(push_constant, scalar) uniform PushBlock { RooflineConstants pc; };

// Closest-hit: the distance and the geometric normal facing the ray; miss: hitT = -1.
struct RooflinePayload {
  vec3 normal;
  float hitT;
};

#endif
