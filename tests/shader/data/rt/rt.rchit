#version 460
#extension GL_EXT_ray_tracing : require
#extension GL_EXT_nonuniform_qualifier : require
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"

layout(location = 0) rayPayloadInEXT Payload payload;
hitAttributeEXT vec2 bary;

void main() {
  uint id = uint(gl_InstanceCustomIndexEXT);
  vec4 base = materials.baseColor[id];
  vec3 tex = texture(textures[nonuniformEXT(id)], bary).rgb;
  atomicAdd(counters.rays, pc.flags);
  payload.color = base.rgb * tex;
}
