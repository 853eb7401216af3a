#version 460
#extension GL_GOOGLE_include_directive : require
// One a-trous iteration (SVGF's spatial filter): a 3x3 kernel with taps `step` pixels apart, each
// tap weighted by how alike its surface is (normal, depth) and its demodulated luminance (a Gaussian of the
// difference in standard deviations of the pixel's mean: where the mean is precise, only taps as bright as it
// count, so the filter's reach shrinks as samples accumulate). The variance is carried along as the filtered
// mean's (sum of squared weights), which the next iteration reads. Reads one filter plane, writes the other;
// the last iteration also leaves each pixel's squared difference from the raw mean for final.comp's bias.
#include "common.glsl"

// The filtered value of pixel p (index i) from the plane starting at `source`. `squaring`: see normalWeight.
// The weights are computed without branches (selects): a CPU driver runs every lane through both sides of a
// branch anyway, and a loop whose body has fewer branches runs faster there.
vec4 filterPixel(ivec2 p, uint i, uint source, const bool squaring) {
  const vec4 center = filtered[source + i];
  const vec4 geometryP = geometry[i];
  const float gradientP = gradient[i];
  const bool missP = geometryP.w < 0.0;
  const float lumP = luminance(center.rgb);
  // 2 sigma^2 V: a tap sigmaLuminance standard deviations away weighs exp(-1/2).
  const float reach = 2.0 * pc.sigmaLuminance * pc.sigmaLuminance * max(center.a, 0.0);
  const float center2 = WB_DENOISE_KERNEL_CENTER * WB_DENOISE_KERNEL_CENTER;
  vec3 sum = center.rgb * center2;
  float weights = center2;
  float variance = center.a * center2 * center2;
  for (int y = -1; y <= 1; ++y) {
    for (int x = -1; x <= 1; ++x) {
      const ivec2 q = p + ivec2(x, y) * int(pc.step);
      // A tap off the image does not count, nor a miss for a hit or a hit for a miss.
      if ((x == 0 && y == 0) || !insideImage(q)) continue;
      const uint j = pixelIndex(q);
      const vec4 c = filtered[source + j];
      const vec4 geometryQ = geometry[j];
      const bool missQ = geometryQ.w < 0.0, hits = !missP && !missQ;
      // The geometry's and the luminance's weights in one exponential.
      const float normal = normalWeight(geometryP.xyz, geometryQ.xyz, squaring);
      const float depth =
          depthExponent(geometryP.w, gradientP, geometryQ.w, float(pc.step) * length(vec2(x, y)));
      const float difference = luminance(c.rgb) - lumP;
      const float luminanceExponent =
          reach > 0.0 ? difference * difference / reach : (difference == 0.0 ? 0.0 : 1.0e30);
      const float exponent = (hits ? depth : 0.0) + (pc.sigmaLuminance > 0.0 ? luminanceExponent : 0.0);
      const float w = kernelWeight(x) * kernelWeight(y) * (hits ? normal : 1.0) * exp(-exponent);
      if (missP == missQ) {
        sum += w * c.rgb;
        weights += w;
        variance += w * w * max(c.a, 0.0);
      }
    }
  }
  return vec4(sum / weights, variance / (weights * weights));
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const uint i = pixelIndex(p), source = pc.source * planeSize(), destination = (pc.source ^ 1u) * planeSize();
  // One branch per pixel around the whole loop, with a loop for each case (see normalWeight).
  vec4 result;
  if (pc.sigmaNormal == 128.0) {
    result = filterPixel(p, i, source, true);
  } else {
    result = filterPixel(p, i, source, false);
  }
  filtered[destination + i] = result;
  if (pc.last != 0u) {
    const vec2 raw = handover[i].xy;
    const float d = luminance(result.rgb) - raw.x;
    bias[i] = d * d - raw.y;
  }
}
