#version 460
#extension GL_GOOGLE_include_directive : require
// The denoiser's first pass, per pixel: the radiance demodulated by the first-hit albedo, the variance of one
// sample's demodulated luminance (from the path tracer's running mean of luminance^2; -1 below 2 samples), and
// the guide the edge-stopping weights read: the first-hit normal (unit length) and depth. Also the raw mean's
// demodulated luminance, which the later passes compare the filtered one with, and the samples per pixel: the
// passes up to the last read only the denoiser's buffers (a CPU driver loads from a buffer for much less than
// from an image).
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_RADIANCE, rgba32f) uniform readonly image2D radianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_ALBEDO, rgba16f) uniform readonly image2D albedoImage;
layout(set = 0, binding = WB_DENOISE_BIND_NORMAL, rgba16f) uniform readonly image2D normalImage;
layout(set = 0, binding = WB_DENOISE_BIND_STATS, rgba32f) uniform readonly image2D statsImage;

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const uint i = pixelIndex(p);
  const vec4 radiance = imageLoad(radianceImage, p);
  const vec3 albedo = demodulationAlbedo(imageLoad(albedoImage, p).rgb);
  const vec3 demodulated = radiance.rgb / albedo;
  const float n = radiance.a;
  const float lumDemodulated = luminance(demodulated);
  // One sample's luminance variance, scaled to the demodulated radiance (the ratio of the luminances).
  float variance = -1.0;
  if (n >= 2.0) {
    const float lum = luminance(radiance.rgb);
    const float lum2 = imageLoad(statsImage, p).r;
    const float scale = lum > 0.0 && lumDemodulated > 0.0 ? lumDemodulated / lum : 1.0 / luminance(albedo);
    variance = max(lum2 - lum * lum, 0.0) * n / (n - 1.0) * scale * scale;
  }
  filtered[i] = vec4(demodulated, variance);  // plane 0
  handover[i] = vec4(lumDemodulated, 0.0, n, 0.0);

  const vec4 normalDepth = imageLoad(normalImage, p);
  geometry[i] = vec4(unitNormal(normalDepth.xyz), normalDepth.a);
}
