#version 460
#extension GL_GOOGLE_include_directive : require
// One a-trous iteration (SVGF's spatial filter): a 5x5 B3-spline kernel with taps `step` pixels apart, each
// tap weighted by how alike its surface is (normal, depth) and its demodulated luminance (a Gaussian of the
// difference in standard deviations of the pixel's mean: where the mean is precise, only taps as bright as it count, so the
// filter's reach shrinks as samples accumulate). The variance is carried along as the filtered mean's
// (sum of squared weights), which the next iteration reads. Reads ping and writes pong, or the other way.
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_GUIDE, rgba32f) uniform readonly image2D guideImage;
layout(set = 0, binding = WB_DENOISE_BIND_PING, rgba32f) uniform image2D pingImage;
layout(set = 0, binding = WB_DENOISE_BIND_PONG, rgba32f) uniform image2D pongImage;

vec4 source(ivec2 q) { return pc.source == 0u ? imageLoad(pingImage, q) : imageLoad(pongImage, q); }

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const vec4 center = source(p);
  const vec4 guideP = imageLoad(guideImage, p);
  const vec3 nP = octDecode(guideP.xy);
  const bool missP = guideP.z < 0.0;
  const float lumP = luminance(center.rgb);
  // 2 sigma^2 V: a tap sigmaLuminance standard deviations away weighs exp(-1/2).
  const float reach = 2.0 * pc.sigmaLuminance * pc.sigmaLuminance * max(center.a, 0.0);
  vec3 sum = center.rgb * (0.375 * 0.375);
  float weights = 0.375 * 0.375;
  float variance = center.a * (0.375 * 0.375) * (0.375 * 0.375);
  for (int y = -2; y <= 2; ++y) {
    for (int x = -2; x <= 2; ++x) {
      if (x == 0 && y == 0) continue;
      const ivec2 q = p + ivec2(x, y) * int(pc.step);
      if (!insideImage(q)) continue;
      const vec4 c = source(q);
      const vec4 guideQ = imageLoad(guideImage, q);
      // The geometry's and the luminance's weights in one exponential.
      float w = kernelWeight(x) * kernelWeight(y);
      float exponent = 0.0;
      const bool missQ = guideQ.z < 0.0;
      if (missP || missQ) {
        if (missP != missQ) continue;
      } else {
        w *= normalWeight(nP, octDecode(guideQ.xy));
        exponent = depthExponent(guideP, guideQ, float(pc.step) * length(vec2(x, y)));
      }
      if (pc.sigmaLuminance > 0.0) {
        const float difference = luminance(c.rgb) - lumP;
        exponent += reach > 0.0 ? difference * difference / reach : (difference == 0.0 ? 0.0 : 1.0e30);
      }
      w *= exp(-exponent);
      sum += w * c.rgb;
      weights += w;
      variance += w * w * max(c.a, 0.0);
    }
  }
  const vec4 filtered = vec4(sum / weights, variance / (weights * weights));
  if (pc.source == 0u) {
    imageStore(pongImage, p, filtered);
  } else {
    imageStore(pingImage, p, filtered);
  }
}
