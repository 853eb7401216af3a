// The heat maps' colours (the window's debug views, the cost maps written by `render --aov cost`), defined
// once for C++ and GLSL: a perceptual blue -> green -> yellow -> red ramp for t in [0, 1].
#ifndef WB_HEAT_RAMP_H
#define WB_HEAT_RAMP_H
#include "glsl_cpp.h"

WB_NAMESPACE_BEGIN

WB_FN vec3 heatRamp(float t) {
  t = clamp(t, 0.0f, 1.0f);
  const vec3 c0 = vec3(0.05f, 0.05f, 0.35f);
  const vec3 c1 = vec3(0.0f, 0.6f, 0.9f);
  const vec3 c2 = vec3(0.2f, 0.85f, 0.3f);
  const vec3 c3 = vec3(1.0f, 0.85f, 0.1f);
  const vec3 c4 = vec3(0.95f, 0.1f, 0.05f);
  if (t < 0.25f) return mix(c0, c1, t * 4.0f);
  if (t < 0.5f) return mix(c1, c2, (t - 0.25f) * 4.0f);
  if (t < 0.75f) return mix(c2, c3, (t - 0.5f) * 4.0f);
  return mix(c3, c4, (t - 0.75f) * 4.0f);
}

WB_NAMESPACE_END

#endif
