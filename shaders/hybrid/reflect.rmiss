#version 460
#extension GL_GOOGLE_include_directive : require
// Reflection rays that escape: the raygen adds the environment.
#include "rt_common.glsl"
#include "reflect_payload.glsl"

layout(location = REFLECTION_PAYLOAD_LOCATION) rayPayloadInEXT ReflectionPayload payload;

void main() { payload.hit = 0u; }
