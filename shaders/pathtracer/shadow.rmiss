#version 460
#extension GL_GOOGLE_include_directive : require
// Shadow miss: the shadow ray (traced by raygen for a light sample of closest-hit) reached its light.
#include "common.glsl"
#include "payload.glsl"

layout(location = PATH_PAYLOAD_LOCATION) rayPayloadInEXT PathPayload payload;

void main() { payload.status = PAYLOAD_UNOCCLUDED; }
