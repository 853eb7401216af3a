#version 460
#extension GL_GOOGLE_include_directive : require
// Environment miss: the radiance of the environment along the ray, MIS-weighted against environment NEE, and of
// the disc of every sun of angular size the ray points into, MIS-weighted against the sun's cone sample.
#include "common.glsl"
#include "payload.glsl"
#include "environment.glsl"
#include "../shared/sun.h"

layout(location = PATH_PAYLOAD_LOCATION) rayPayloadInEXT PathPayload payload;

void main() {
  const vec3 dir = gl_WorldRayDirectionEXT;
  // A BRDF-sampled ray (pdf > 0) that escapes is the second strategy for the lights NEE sampled (MIS), or, with
  // light sampling only, reaches them through NEE alone (weight 0). Camera rays and BRDF sampling alone: weight 1.
  const bool brdfSampled = payload.bounce > 0u && payload.pdf > 0.0 && (pc.flags & WB_FLAG_NO_NEE) == 0u;
  const bool lightSamplingOnly = brdfSampled && (pc.flags & WB_FLAG_NO_BRDF_MIS) != 0u;
  float misWeight = 1.0;
  if (lightSamplingOnly) {
    misWeight = 0.0;
  } else if (brdfSampled) {
    misWeight = powerHeuristic(1.0, payload.pdf, 1.0, frame.envSelectProbability * envPdf(dir));
  }
  payload.radiance = envRadiance(dir) * misWeight;
  vec3 sun = vec3(0.0);
  for (uint i = 0u; i < WB_LIGHT_COUNT; ++i) {
    const DirectionalLight light = lights[i];
    const vec3 le = sunRadianceAlong(dir, light.direction, light.cosAngularRadius, light.radiance);
    if (le == vec3(0.0)) continue;
    const float w = lightSamplingOnly ? 0.0
                    : brdfSampled     ? powerHeuristic(1.0, payload.pdf, 1.0, sunConePdf(light.cosAngularRadius))
                                      : 1.0;
    sun += le * w;
  }
  payload.radiance += sun;
#if WB_INSPECT
  const uint slot = inspectSlot();
  if (slot != WB_INSPECT_NONE) {
    inspectSamples[slot].escapeEnvironment = envRadiance(dir);
    inspectSamples[slot].escapeMis = misWeight;
    inspectSamples[slot].escapeSun = sun;
  }
#endif
  payload.status = PAYLOAD_MISS;
  payload.hitT = -1.0;
  payload.albedo = vec3(0.0);
  payload.normal = vec3(0.0);
  payload.geoNormal = vec3(0.0);
}
