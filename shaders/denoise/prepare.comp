#version 460
#extension GL_GOOGLE_include_directive : require
// The denoiser's first pass, per pixel: the radiance demodulated by the first-hit albedo, the variance of one
// sample's demodulated luminance (from the path tracer's running mean of luminance^2; -1 below 2 samples), and
// the guide the edge-stopping weights read: the first-hit normal (octahedral), depth and how much the depth
// changes per pixel there (the smaller one-sided difference on each axis, so that an edge does not count).
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_RADIANCE, rgba32f) uniform readonly image2D radianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_ALBEDO, rgba16f) uniform readonly image2D albedoImage;
layout(set = 0, binding = WB_DENOISE_BIND_NORMAL, rgba16f) uniform readonly image2D normalImage;
layout(set = 0, binding = WB_DENOISE_BIND_STATS, rgba32f) uniform readonly image2D statsImage;
layout(set = 0, binding = WB_DENOISE_BIND_GUIDE, rgba32f) uniform writeonly image2D guideImage;
layout(set = 0, binding = WB_DENOISE_BIND_PING, rgba32f) uniform writeonly image2D pingImage;

float depthAt(ivec2 q, float fallback) {
  return insideImage(q) ? imageLoad(normalImage, q).a : fallback;
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (!insideImage(p)) return;
  const vec4 radiance = imageLoad(radianceImage, p);
  const vec3 albedo = demodulationAlbedo(imageLoad(albedoImage, p).rgb);
  const vec3 demodulated = radiance.rgb / albedo;
  const float n = radiance.a;
  // One sample's luminance variance, scaled to the demodulated radiance (the ratio of the luminances).
  float variance = -1.0;
  if (n >= 2.0) {
    const float lum = luminance(radiance.rgb), lumDemodulated = luminance(demodulated);
    const float lum2 = imageLoad(statsImage, p).r;
    const float scale = lum > 0.0 && lumDemodulated > 0.0 ? lumDemodulated / lum : 1.0 / luminance(albedo);
    variance = max(lum2 - lum * lum, 0.0) * n / (n - 1.0) * scale * scale;
  }
  imageStore(pingImage, p, vec4(demodulated, variance));

  const vec4 normalDepth = imageLoad(normalImage, p);
  const float z = normalDepth.a;
  const float dx = min(abs(depthAt(p + ivec2(1, 0), 1.0e30) - z), abs(z - depthAt(p - ivec2(1, 0), 1.0e30)));
  const float dy = min(abs(depthAt(p + ivec2(0, 1), 1.0e30) - z), abs(z - depthAt(p - ivec2(0, 1), 1.0e30)));
  const float gradient = min(length(vec2(dx, dy)), abs(z));
  imageStore(guideImage, p, vec4(octEncode(normalDepth.xyz), z, gradient));
}
