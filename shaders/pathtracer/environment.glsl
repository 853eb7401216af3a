// The environment: radiance lookup, importance sampling and its pdf.
#ifndef WB_PT_ENVIRONMENT_GLSL
#define WB_PT_ENVIRONMENT_GLSL
#include "../shared/sampling_math.h"

vec3 envRadiance(vec3 dir) {
  if (frame.envMapPresent == 0u) return frame.envColor.rgb * frame.envIntensity;
  const vec2 uv = directionToEquirect(dir, frame.envRotation);
  return textureLod(envMap, uv, 0.0).rgb * frame.envIntensity;
}

float envPdf(vec3 dir) { return 0.25 * kInvPi; }

vec3 envSample(vec3 u, out vec3 dir, out float pdf) {
  dir = sampleUniformSphere(vec2(u.x, u.y));
  pdf = 0.25 * kInvPi;
  return envRadiance(dir);
}

#endif
