// The environment: radiance lookup, importance sampling (alias table) and its pdf, all consistent with the
// equirectangular map the host uploaded (a 1x1 map for a constant colour).
#ifndef WB_PT_ENVIRONMENT_GLSL
#define WB_PT_ENVIRONMENT_GLSL
#include "../shared/env_sampling.h"

// The environment's radiance along dir (shared/scene.glsl), the scene's kind of environment compiled in.
vec3 envRadiance(vec3 dir) {
  return environmentRadiance(WB_ENV_MODE, dir, frame.envColor.rgb * frame.envIntensity, frame.envRotation,
                             frame.envIntensity);
}

float envPdf(vec3 dir) { return envPdf(dir, frame.envWidth, frame.envHeight, frame.envRotation); }

// Returns the radiance of a sampled direction; pdf 0 marks a sample to skip.
vec3 envSample(vec3 u, out vec3 dir, out float pdf) {
  const EnvSample s = envSample(u, frame.envWidth, frame.envHeight, frame.envRotation);
  dir = s.dir;
  pdf = s.pdf;
  return pdf > 0.0 ? envRadiance(dir) : vec3(0.0);
}

#endif
