// Exposure + tonemap curves + sRGB encoding: the same curves as src/eval/image.cpp (the PNG writer), so the
// window shows what `workbench render` writes.
#ifndef WB_TONEMAP_GLSL
#define WB_TONEMAP_GLSL
#include "display_types.h"
#include "../shared/heat_ramp.h"  // heatRamp

float tonemapChannel(float v, uint op) {
  // As src/eval/image.cpp: NaN is black; +inf and huge values are white (the curves would overflow to NaN).
  if (isnan(v)) return 0.0;
  v = clamp(v, 0.0, 1e15);
  if (op == WB_TONEMAP_CLAMP) return min(v, 1.0);
  if (op == WB_TONEMAP_REINHARD) return v / (1.0 + v);
  // Narkowicz 2015 fit of the ACES filmic curve.
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((v * (a * v + b)) / (v * (c * v + d) + e), 0.0, 1.0);
}

vec3 tonemap(vec3 linear, float exposureScale, uint op) {
  const vec3 v = linear * exposureScale;
  return vec3(tonemapChannel(v.r, op), tonemapChannel(v.g, op), tonemapChannel(v.b, op));
}

float linearToSrgb(float v) {
  v = clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

vec3 linearToSrgb(vec3 v) { return vec3(linearToSrgb(v.r), linearToSrgb(v.g), linearToSrgb(v.b)); }

#endif
