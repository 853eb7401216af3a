#version 460
#extension GL_GOOGLE_include_directive : require
// The last pass: the filtered radiance modulated by the albedo again, then handed over to the raw mean as the
// mean becomes precise. The output is raw + a (filtered - raw) with a = V / (V + Vf + (tau L)^2): V is the
// variance of the raw mean, Vf the filtered one's, and tau L the filter's error assumed relative to its
// luminance L (its bias, which no variance shows). That is the weight that minimises the error of two
// independent estimates of those errors; as samples accumulate V falls as 1/N while (tau L)^2 stays, so a
// tends to 0 and the output to the path tracer's own image: the denoiser is consistent by construction.
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_RADIANCE, rgba32f) uniform readonly image2D radianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_ALBEDO, rgba16f) uniform readonly image2D albedoImage;
layout(set = 0, binding = WB_DENOISE_BIND_PING, rgba32f) uniform readonly image2D pingImage;
layout(set = 0, binding = WB_DENOISE_BIND_PONG, rgba32f) uniform readonly image2D pongImage;
layout(set = 0, binding = WB_DENOISE_BIND_VARIANCE, r32f) uniform readonly image2D varianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_OUTPUT, rgba32f) uniform writeonly image2D outputImage;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(pc.imageSize.x) || p.y >= int(pc.imageSize.y)) return;
  const vec4 raw = imageLoad(radianceImage, p);
  if (!insideImage(p)) {
    imageStore(outputImage, p, raw);
    return;
  }
  const vec4 filtered = pc.source == 0u ? imageLoad(pingImage, p) : imageLoad(pongImage, p);
  const vec3 albedo = demodulationAlbedo(imageLoad(albedoImage, p).rgb);
  const vec3 denoised = filtered.rgb * albedo;
  float a = 1.0;
  if (pc.handoverTau >= 0.0) {
    const float v = imageLoad(varianceImage, p).r;
    const float bias = pc.handoverTau * luminance(filtered.rgb);
    const float total = v + max(filtered.a, 0.0) + bias * bias;
    a = total > 0.0 ? v / total : 0.0;
  }
  imageStore(outputImage, p, vec4(raw.rgb + a * (denoised - raw.rgb), raw.a));
}
