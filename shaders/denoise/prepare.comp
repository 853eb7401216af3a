#version 460
#extension GL_GOOGLE_include_directive : require
// The denoiser's first pass, per pixel: the radiance demodulated by the first-hit albedo, the variance of one
// sample's demodulated luminance (from the path tracer's running mean of luminance^2; -1 below 2 samples), and
// the guide the edge-stopping weights read: the first-hit normal (unit length), depth and
// how much the depth changes per pixel there (the smaller one-sided difference on each axis, so that an edge
// does not count). Also the raw mean's demodulated luminance, which the last pass compares the filtered one
// with around each pixel: the later passes read only the denoiser's buffers.
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_RADIANCE, rgba32f) uniform readonly image2D radianceImage;
layout(set = 0, binding = WB_DENOISE_BIND_ALBEDO, rgba16f) uniform readonly image2D albedoImage;
layout(set = 0, binding = WB_DENOISE_BIND_NORMAL, rgba16f) uniform readonly image2D normalImage;
layout(set = 0, binding = WB_DENOISE_BIND_STATS, rgba32f) uniform readonly image2D statsImage;
layout(std430, set = 0, binding = WB_DENOISE_BIND_GEOMETRY) writeonly buffer DenoiseGeometryBlock {
  vec4 geometry[];
};
layout(std430, set = 0, binding = WB_DENOISE_BIND_FILTER) writeonly buffer DenoiseFilterBlock {
  vec4 filtered[];
};
layout(std430, set = 0, binding = WB_DENOISE_BIND_GRADIENT) writeonly buffer DenoiseGradientBlock {
  float gradient[];
};
layout(std430, set = 0, binding = WB_DENOISE_BIND_HANDOVER) writeonly buffer DenoiseHandoverBlock {
  vec2 handover[];
};

float depthAt(ivec2 q, float fallback) {
  return insideImage(q) ? imageLoad(normalImage, q).a : fallback;
}

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
  handover[i].x = lumDemodulated;

  const vec4 normalDepth = imageLoad(normalImage, p);
  const float z = normalDepth.a;
  const float dx = min(abs(depthAt(p + ivec2(1, 0), 1.0e30) - z), abs(z - depthAt(p - ivec2(1, 0), 1.0e30)));
  const float dy = min(abs(depthAt(p + ivec2(0, 1), 1.0e30) - z), abs(z - depthAt(p - ivec2(0, 1), 1.0e30)));
  gradient[i] = min(length(vec2(dx, dy)), abs(z));
  geometry[i] = vec4(unitNormal(normalDepth.xyz), z);
}
