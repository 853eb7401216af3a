#version 460
#extension GL_GOOGLE_include_directive : require
// Nothing hit (camera and bounce rays: escaped; shadow rays: the light is visible).
#include "common.glsl"

layout(location = 0) rayPayloadInEXT RooflinePayload payload;

void main() { payload.hitT = -1.0; }
