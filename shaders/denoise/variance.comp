#version 460
#extension GL_GOOGLE_include_directive : require
// The variance of each pixel's mean (demodulated luminance), which sets how far the filter reaches. A pixel's
// own estimate (from its samples; below 2 samples, its squared distance from the median of its 3x3
// neighbourhood) is noisy; the median of the estimates over the 3x3 neighbourhood on the same surface is
// steadier, and unlike a mean it does not take a calm pixel's variance from a few noisy neighbours across a
// luminance edge the geometry does not show (an emitter's rim). The larger of the two, divided by the
// pixel's samples: a firefly keeps its own large variance, so the filter reaches out to dilute it.
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_RADIANCE, rgba32f) uniform readonly image2D radianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_GUIDE, rgba32f) uniform readonly image2D guideImage;
layout(set = 0, binding = WB_DENOISE_BIND_PING, rgba32f) uniform readonly image2D pingImage;
layout(set = 0, binding = WB_DENOISE_BIND_PONG, rgba32f) uniform writeonly image2D pongImage;
layout(set = 0, binding = WB_DENOISE_BIND_VARIANCE, r32f) uniform writeonly image2D varianceImage;

float median9(inout float v[9]) {
  for (int i = 1; i < 9; ++i) {
    const float x = v[i];
    int j = i - 1;
    while (j >= 0 && v[j] > x) {
      v[j + 1] = v[j];
      --j;
    }
    v[j + 1] = x;
  }
  return v[4];
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const vec4 center = imageLoad(pingImage, p);
  const vec4 guideP = imageLoad(guideImage, p);
  const vec3 nP = octDecode(guideP.xy);
  const float n = imageLoad(radianceImage, p).a;
  const bool own = n >= 2.0;
  // Per tap: its per-sample variance (own) or its luminance (below 2 samples); taps off the surface, off the
  // image or without an estimate count as the pixel itself.
  const float self = own ? max(center.a, 0.0) : luminance(center.rgb);
  float v[9];
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      const ivec2 q = p + ivec2(x, y);
      float value = self;
      if (insideImage(q) && geometryWeight(guideP, nP, imageLoad(guideImage, q), length(vec2(x, y))) > 0.5) {
        const vec4 c = imageLoad(pingImage, q);
        if (!own) {
          value = luminance(c.rgb);
        } else if (c.a >= 0.0) {
          value = c.a;
        }
      }
      v[(y + 1) * 3 + x + 1] = value;
    }
  }
  float variance = 0.0;
  if (own) {
    variance = max(self, median9(v));
  } else if (n > 0.0) {
    // One sample: the median absolute deviation (times 1.4826: a normal distribution's standard deviation).
    const float m = median9(v);
    for (int i = 0; i < 9; ++i) v[i] = abs(v[i] - m);
    const float spread = 1.4826 * median9(v);
    variance = max((self - m) * (self - m), spread * spread);
  }
  const float varianceOfMean = n > 0.0 ? variance / n : 0.0;
  imageStore(pongImage, p, vec4(center.rgb, varianceOfMean));
  imageStore(varianceImage, p, vec4(varianceOfMean));
}
