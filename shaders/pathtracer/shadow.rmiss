#version 460
#extension GL_GOOGLE_include_directive : require
#include "common.glsl"
#include "payload.glsl"

layout(location = SHADOW_PAYLOAD_LOCATION) rayPayloadInEXT ShadowPayload shadow;

void main() { shadow.visible = 1u; }
