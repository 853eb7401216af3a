#version 460
#extension GL_GOOGLE_include_directive : require
// The variance of each pixel's mean (demodulated luminance), which sets how far the filter reaches. A pixel's
// own estimate (from its samples; below 2 samples, its squared distance from the median of its 3x3
// neighbourhood) is noisy; the median of the estimates over the 3x3 neighbourhood on the same surface is
// steadier, and unlike a mean it does not take a calm pixel's variance from a few noisy neighbours across a
// luminance edge the geometry does not show (an emitter's rim). The larger of the two, divided by the
// pixel's samples: a firefly keeps its own large variance, so the filter reaches out to dilute it. Below
// WB_DENOISE_SHORT_HISTORY samples the own estimates are too few to trust (from 2 samples most pixels
// estimate well below the true variance, and the filter would hardly touch them): the spread of the
// neighbourhood's means, times the samples, is taken too where it is larger (SVGF's spatial estimate for a
// short history).
// The pass also works out how much the depth changes per pixel at p (the smaller one-sided difference on each
// axis, so that an edge does not count), which the edge-stopping weights here and in the a-trous passes
// compare depths with. Reads filter plane 0, writes plane 1, the gradient and the hand-over's variance.
#include "common.glsl"

// The median of nine values by a fixed network of compare-exchanges (Paeth; no data-dependent loop, which a
// CPU driver runs for as long as its slowest lane). Each exchange keeps both values: v stays a permutation.
void exchange(inout float a, inout float b) {
  const float lo = min(a, b), hi = max(a, b);
  a = lo;
  b = hi;
}
float median9(inout float v[9]) {
  exchange(v[1], v[2]);
  exchange(v[4], v[5]);
  exchange(v[7], v[8]);
  exchange(v[0], v[1]);
  exchange(v[3], v[4]);
  exchange(v[6], v[7]);
  exchange(v[1], v[2]);
  exchange(v[4], v[5]);
  exchange(v[7], v[8]);
  exchange(v[0], v[3]);
  exchange(v[5], v[8]);
  exchange(v[4], v[7]);
  exchange(v[3], v[6]);
  exchange(v[1], v[4]);
  exchange(v[2], v[5]);
  exchange(v[4], v[7]);
  exchange(v[4], v[2]);
  exchange(v[6], v[4]);
  exchange(v[4], v[2]);
  return v[4];
}

// Which taps of the 3x3 neighbourhood are on p's surface (bit (y + 1) * 3 + x + 1; off the image: not).
// `squaring`: see normalWeight.
uint sameSurface(ivec2 p, vec4 geometryP, float gradientP, const bool squaring) {
  uint mask = 0u;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      const ivec2 q = p + ivec2(x, y);
      if (insideImage(q) &&
          geometryWeight(geometryP, gradientP, geometry[pixelIndex(q)], length(vec2(x, y)), squaring) >
              WB_DENOISE_SAME_SURFACE)
        mask |= 1u << uint((y + 1) * 3 + x + 1);
    }
  }
  return mask;
}

// Per tap of the 3x3 neighbourhood: its per-sample variance (own) or its luminance (below 2 samples); taps off
// the surface, off the image or without an estimate count as the pixel itself (self).
void gatherTaps(ivec2 p, uint surface, bool own, float self, inout float v[9]) {
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      const int k = (y + 1) * 3 + x + 1;
      float value = self;
      if ((surface & (1u << uint(k))) != 0u) {
        const vec4 c = filtered[pixelIndex(p + ivec2(x, y))];
        if (!own) {
          value = luminance(c.rgb);
        } else if (c.a >= 0.0) {
          value = c.a;
        }
      }
      v[k] = value;
    }
  }
}

// The spread of the 3x3 neighbourhood's values around their median, as a standard deviation (the median
// absolute deviation times 1.4826: a normal distribution's), and that median. v is reordered.
vec2 robustSpread(inout float v[9]) {
  const float m = median9(v);
  for (int k = 0; k < 9; ++k) v[k] = abs(v[k] - m);
  return vec2(1.4826 * median9(v), m);
}

float depthAt(ivec2 q) { return insideImage(q) ? geometry[pixelIndex(q)].w : 1.0e30; }

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const uint i = pixelIndex(p);
  const vec4 center = filtered[i];
  const vec4 geometryP = geometry[i];
  const float z = geometryP.w;
  const float dx = min(abs(depthAt(p + ivec2(1, 0)) - z), abs(z - depthAt(p - ivec2(1, 0))));
  const float dy = min(abs(depthAt(p + ivec2(0, 1)) - z), abs(z - depthAt(p - ivec2(0, 1))));
  const float gradientP = min(length(vec2(dx, dy)), abs(z));
  gradient[i] = gradientP;
  const float n = handover[i].z;
  const bool own = n >= 2.0;
  const float self = own ? max(center.a, 0.0) : luminance(center.rgb);
  uint surface;
  if (pc.sigmaNormal == 128.0) {
    surface = sameSurface(p, geometryP, gradientP, true);
  } else {
    surface = sameSurface(p, geometryP, gradientP, false);
  }
  float v[9];
  gatherTaps(p, surface, own, self, v);
  float variance = 0.0;
  if (own) {
    variance = max(self, median9(v));
    if (n < WB_DENOISE_SHORT_HISTORY) {
      // The means' spread: the variance of a mean, times n for one sample's.
      gatherTaps(p, surface, false, luminance(center.rgb), v);
      const float spread = robustSpread(v).x;
      variance = max(variance, n * spread * spread);
    }
  } else if (n > 0.0) {
    // One sample: the neighbourhood's spread, or the pixel's own distance from its median where larger.
    const vec2 s = robustSpread(v);
    variance = max((self - s.y) * (self - s.y), s.x * s.x);
  }
  const float varianceOfMean = n > 0.0 ? variance / n : 0.0;
  filtered[planeSize() + i] = vec4(center.rgb, varianceOfMean);
  handover[i].y = varianceOfMean;
}
