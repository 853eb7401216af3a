#version 460
#extension GL_GOOGLE_include_directive : require
// Miss shader of the occlusion ray types (sun shadow rays and ambient occlusion rays): nothing was in the way.
#include "rt_common.glsl"

layout(location = OCCLUSION_PAYLOAD_LOCATION) rayPayloadInEXT uint visible;

void main() { visible = 1u; }
