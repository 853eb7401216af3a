#version 460
#extension GL_GOOGLE_include_directive : require
#define WB_STAGE WB_STAGE_SHADOW_MISS
// Shadow miss: the shadow ray (traced by raygen for a light sample of closest-hit) reached its light.
#include "common.glsl"
#include "payload.glsl"

layout(location = PATH_PAYLOAD_LOCATION) rayPayloadInEXT PathPayload payload;

void main() {
  wbDebugAtBounce(payload.bounce);
  payload.status = PAYLOAD_UNOCCLUDED;
}
