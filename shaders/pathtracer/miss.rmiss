#version 460
#extension GL_GOOGLE_include_directive : require
// Environment miss: the radiance of the environment along the ray, MIS-weighted against environment NEE.
#include "common.glsl"
#include "payload.glsl"
#include "environment.glsl"

layout(location = PATH_PAYLOAD_LOCATION) rayPayloadInEXT PathPayload payload;

void main() {
  const vec3 dir = gl_WorldRayDirectionEXT;
  float misWeight = 1.0;
  // A BRDF-sampled ray (pdf > 0) that escapes is the second strategy for the environment when NEE sampled it too.
  if (payload.bounce > 0u && payload.pdf > 0.0 && (pc.flags & (WB_FLAG_NO_NEE | WB_FLAG_NO_BRDF_MIS)) == 0u) {
    misWeight = powerHeuristic(1.0, payload.pdf, 1.0, frame.envSelectProbability * envPdf(dir));
  } else if (payload.bounce > 0u && payload.pdf > 0.0 && (pc.flags & WB_FLAG_NO_BRDF_MIS) != 0u &&
             (pc.flags & WB_FLAG_NO_NEE) == 0u) {
    misWeight = 0.0;  // light sampling only: the environment is reached through NEE alone
  }
  payload.radiance = envRadiance(dir) * misWeight;
#if WB_INSPECT
  const uint slot = inspectSlot();
  if (slot != WB_INSPECT_NONE) {
    inspectSamples[slot].escapeEnvironment = envRadiance(dir);
    inspectSamples[slot].escapeMis = misWeight;
  }
#endif
  payload.status = PAYLOAD_MISS;
  payload.hitT = -1.0;
  payload.albedo = vec3(0.0);
  payload.normal = vec3(0.0);
  payload.geoNormal = vec3(0.0);
}
