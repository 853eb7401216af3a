// Environment-map importance sampling with an alias table (one EnvAliasEntry per pixel, row-major, row 0 = +Y),
// shared by shaders and CPU tests. Pixel weights (built on the host, src/sampling/environment.cpp) are
// luminance * sin(theta_center); the table gives O(1) sampling of a pixel, then a uniform position inside it in
// (u,v). Hence, for a direction with polar angle theta inside pixel i:
//   pdf_solid_angle = entry[i].pdf * W * H / (2 pi^2 sin(theta))
// envPdf(dir) evaluates exactly that; envSample returns envPdf of the direction it produced, so the two agree
// bit for bit. Mapping and rotation: see sampling_math.h (directionToEquirect / equirectToDirection).
//
// Table access: a shader defines, before including this header,
//   #define WB_ENV_ALIAS(i) envAliasBuffer.entries[(i)]      // EnvAliasEntry, binding WB_BIND_ENV_ALIAS
// In C++ the default reads the thread-local pointer wb::gpu::gEnvAlias (set it to EnvironmentMap::alias.data()).
#ifndef WB_ENV_SAMPLING_H
#define WB_ENV_SAMPLING_H
#include "scene_types.h"
#include "sampling_math.h"

WB_NAMESPACE_BEGIN
#ifdef __cplusplus
inline thread_local const EnvAliasEntry* gEnvAlias = nullptr;
#endif
WB_NAMESPACE_END

#ifdef __cplusplus
#ifndef WB_ENV_ALIAS
#define WB_ENV_ALIAS(i) (::wb::gpu::gEnvAlias[(i)])
#endif
#else
#ifndef WB_ENV_ALIAS
#error "define WB_ENV_ALIAS(i) (EnvAliasEntry from the alias-table buffer) before including env_sampling.h"
#endif
#endif

WB_NAMESPACE_BEGIN

struct EnvSample {
  vec3 dir;   // world-space direction towards the environment
  float pdf;  // solid-angle pdf; 0 = invalid sample (pole / zero-weight pixel): skip it
};

// Solid-angle pdf of envSample for a world direction (unit vector).
WB_FN float envPdf(vec3 dir, uint width, uint height, float rotation) {
  vec2 uv = directionToEquirect(dir, rotation);
  uint x = min(uint(max(uv.x, 0.0f) * float(width)), width - 1u);
  uint y = min(uint(max(uv.y, 0.0f) * float(height)), height - 1u);
  float sinTheta = sqrt(max(0.0f, dir.x * dir.x + dir.z * dir.z));  // rotation about Y keeps sin(theta)
  if (!(sinTheta > 0.0f)) return 0.0f;
  float pdfPixel = WB_ENV_ALIAS(y * width + x).pdf;
  return pdfPixel * float(width) * float(height) / (2.0f * kPi * kPi * sinTheta);
}

// u.x picks the table entry, u.y the alias coin (its remainder jitters x inside the pixel), u.z jitters y.
WB_FN EnvSample envSample(vec3 u, uint width, uint height, float rotation) {
  uint n = width * height;
  uint i = min(uint(u.x * float(n)), n - 1u);
  EnvAliasEntry e = WB_ENV_ALIAS(i);
  float jx;
  if (u.y < e.prob) {
    jx = u.y / e.prob;
  } else {
    i = e.alias;
    jx = (u.y - e.prob) / (1.0f - e.prob);
  }
  jx = min(jx, kOneMinusEpsilon);
  uint x = i % width;
  uint y = i / width;
  vec2 uv = vec2((float(x) + jx) / float(width), (float(y) + u.z) / float(height));
  EnvSample s;
  s.dir = equirectToDirection(uv, rotation);
  s.pdf = envPdf(s.dir, width, height, rotation);
  return s;
}

WB_NAMESPACE_END

#endif
