#version 460
#extension GL_GOOGLE_include_directive : require
// One a-trous iteration (SVGF's spatial filter): a 5x5 B3-spline kernel with taps `step` pixels apart, each
// tap weighted by how alike its surface is (normal, depth) and its demodulated luminance (a Gaussian of the
// difference in standard deviations of the pixel's mean: where the mean is precise, only taps as bright as it
// count, so the filter's reach shrinks as samples accumulate). The variance is carried along as the filtered
// mean's (sum of squared weights), which the next iteration reads. Reads one filter plane, writes the other.
#include "common.glsl"

layout(std430, set = 0, binding = WB_DENOISE_BIND_GEOMETRY) readonly buffer DenoiseGeometryBlock {
  vec4 geometry[];
};
layout(std430, set = 0, binding = WB_DENOISE_BIND_FILTER) buffer DenoiseFilterBlock { vec4 filtered[]; };
layout(std430, set = 0, binding = WB_DENOISE_BIND_GRADIENT) readonly buffer DenoiseGradientBlock {
  float gradient[];
};

// The filtered value of pixel p from the plane starting at `source`. `squaring`: see normalWeight.
vec4 filterPixel(ivec2 p, uint source, const bool squaring) {
  const uint i = pixelIndex(p);
  const vec4 center = filtered[source + i];
  const vec4 geometryP = geometry[i];
  const float gradientP = gradient[i];
  const bool missP = geometryP.w < 0.0;
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
      const uint j = pixelIndex(q);
      const vec4 c = filtered[source + j];
      const vec4 geometryQ = geometry[j];
      // The geometry's and the luminance's weights in one exponential.
      float w = kernelWeight(x) * kernelWeight(y);
      float exponent = 0.0;
      const bool missQ = geometryQ.w < 0.0;
      if (missP || missQ) {
        if (missP != missQ) continue;
      } else {
        w *= normalWeight(geometryP.xyz, geometryQ.xyz, squaring);
        exponent = depthExponent(geometryP.w, gradientP, geometryQ.w, float(pc.step) * length(vec2(x, y)));
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
  return vec4(sum / weights, variance / (weights * weights));
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const uint source = pc.source * planeSize(), destination = (pc.source ^ 1u) * planeSize();
  vec4 result;
  if (pc.sigmaNormal == 128.0) {
    result = filterPixel(p, source, true);
  } else {
    result = filterPixel(p, source, false);
  }
  filtered[destination + pixelIndex(p)] = result;
}
