#version 460
#extension GL_GOOGLE_include_directive : require
// The last pass: the filtered radiance modulated by the albedo again, then handed over to the raw mean as the
// mean becomes precise. The output is raw + a (filtered - raw) with a = V / (V + Vf + B): V is the variance of
// the raw mean, Vf the filtered one's and B the filter's squared bias, the larger of (tau L)^2 (an error
// assumed relative to the filtered luminance L, which no variance shows) and the bias the pixel's 5x5
// neighbourhood shows (the mean squared difference of filtered and raw beyond the raw means' variance). That is
// the weight that minimises the error of two independent estimates of those errors; as samples accumulate V
// falls as 1/N while B stays, so a tends to 0 and the output to the path tracer's own image: the denoiser is
// consistent by construction. All in the demodulated luminance.
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_RADIANCE, rgba32f) uniform readonly image2D radianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_ALBEDO, rgba16f) uniform readonly image2D albedoImage;
layout(set = 0, binding = WB_DENOISE_BIND_OUTPUT, rgba32f) uniform writeonly image2D outputImage;

// The squared bias of the filter seen around p: over the 5x5 neighbourhood, the mean of (filtered - raw)^2
// less the mean variance of the raw means (what noise alone puts there), floored at 0. Each pixel's term is
// in the bias buffer (the last a-trous iteration's).
float observedBias2(ivec2 p) {
  float excess = 0.0;
  int n = 0;
  for (int y = -2; y <= 2; ++y) {
    for (int x = -2; x <= 2; ++x) {
      const ivec2 q = p + ivec2(x, y);
      if (!insideImage(q)) continue;
      excess += bias[pixelIndex(q)];
      ++n;
    }
  }
  return max(excess, 0.0) / float(max(n, 1));
}

// The output of pixel p inside the filtered rows: raw + a (denoised - raw).
vec4 handedOver(ivec2 p, vec4 raw) {
  const uint source = pc.source * planeSize(), i = pixelIndex(p);
  const vec4 filteredP = filtered[source + i];
  const vec3 albedo = demodulationAlbedo(imageLoad(albedoImage, p).rgb);
  const vec3 denoised = filteredP.rgb * albedo;
  float a = 1.0;
  if (pc.handoverTau >= 0.0) {
    const float v = handover[i].y;
    const float assumed = pc.handoverTau * luminance(filteredP.rgb);
    const float total = v + max(filteredP.a, 0.0) + max(assumed * assumed, observedBias2(p));
    a = total > 0.0 ? v / total : 0.0;
  }
  return vec4(raw.rgb + a * (denoised - raw.rgb), raw.a);
}

// With pc.window, each workgroup also sums its raw and its output radiance for gain.comp.
const uint kGroupPixels = WB_DENOISE_GROUP_SIZE * WB_DENOISE_GROUP_SIZE;
shared vec3 rawSums[kGroupPixels], outputSums[kGroupPixels];

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  vec4 raw = vec4(0.0), result = vec4(0.0);
  if (p.x < int(pc.imageSize.x) && p.y < int(pc.imageSize.y)) {
    raw = imageLoad(radianceImage, p);
    result = insideImage(p) ? handedOver(p, raw) : raw;  // rows not filtered are copied
    if (pc.window == 0u) {
      imageStore(outputImage, p, result);
    } else {
      filtered[(pc.source ^ 1u) * planeSize() + pixelIndex(p)] = result;  // a CPU driver stores to a buffer faster
    }
  }
  if (pc.window == 0u) return;
  const uint l = gl_LocalInvocationIndex;
  rawSums[l] = raw.rgb;
  outputSums[l] = result.rgb;
  // One barrier and one invocation summing: a CPU driver runs a group's invocations on one thread, where each
  // barrier of a tree reduction costs a switch of all of them.
  barrier();
  if (l == 0u) {
    vec3 rawSum = vec3(0.0), outputSum = vec3(0.0);
    for (uint k = 0u; k < kGroupPixels; ++k) {
      rawSum += rawSums[k];
      outputSum += outputSums[k];
    }
    const uint g = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    tiles[2u * g] = vec4(rawSum, 0.0);
    tiles[2u * g + 1u] = vec4(outputSum, 0.0);
  }
}
