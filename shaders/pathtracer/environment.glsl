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

// Whether next-event estimation samples the environment by the BRDF instead of its alias table: for a constant
// environment (WB_ENV_CONSTANT, or the generic build's 1x1 map of a constant colour) the light sample's ideal
// density is the BRDF's own (the radiance is the same in every direction), so the light sample is a second draw of
// the continuation's density (pathSample, guiding.glsl) and its strategy's pdf for any direction is pathPdf at the
// same vertex; MIS between two draws of one density weighs each 1/2 (the miss shader's weight of a BRDF-sampled
// escape uses payload.pdf as that pdf).
// --define WB_ENV_BRDF_SAMPLING=0: the alias table for every environment (a uniform direction in (u, v) of the
// 1x1 map for a constant one).
#ifndef WB_ENV_BRDF_SAMPLING
#define WB_ENV_BRDF_SAMPLING 1
#endif
bool envSampledByBrdf() {
#if WB_ENV_BRDF_SAMPLING == 0 || WB_ENV_MODE == WB_ENV_NONE
  return false;
#elif WB_ENV_MODE == WB_ENV_CONSTANT
  return true;
#else
  return frame.envMapPresent == 0u;
#endif
}

// Returns the radiance of a sampled direction; pdf 0 marks a sample to skip.
vec3 envSample(vec3 u, out vec3 dir, out float pdf) {
  const EnvSample s = envSample(u, frame.envWidth, frame.envHeight, frame.envRotation);
  dir = s.dir;
  pdf = s.pdf;
  return pdf > 0.0 ? envRadiance(dir) : vec3(0.0);
}

#endif
