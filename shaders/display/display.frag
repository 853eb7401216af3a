#version 460
#extension GL_GOOGLE_include_directive : require
// Shows the path tracer's accumulation (exposure + tonemap + sRGB) or one of its AOV debug views. Rows the
// current sample has not reached yet show the low-resolution preview. With denoise on, the image right of the
// split shows the denoised radiance, left of it the raw one, with a line between.
#include "tonemap.glsl"

layout(set = 0, binding = WB_DISPLAY_BIND_ACCUM, rgba32f) uniform readonly image2D accumImage;
layout(set = 0, binding = WB_DISPLAY_BIND_ALBEDO, rgba16f) uniform readonly image2D albedoImage;
layout(set = 0, binding = WB_DISPLAY_BIND_NORMAL, rgba16f) uniform readonly image2D normalImage;
layout(set = 0, binding = WB_DISPLAY_BIND_INFO, rgba16f) uniform readonly image2D infoImage;
layout(set = 0, binding = WB_DISPLAY_BIND_PREVIEW, rgba32f) uniform readonly image2D previewImage;
layout(set = 0, binding = WB_DISPLAY_BIND_STATS, rgba32f) uniform readonly image2D statsImage;
layout(set = 0, binding = WB_DISPLAY_BIND_DENOISED, rgba32f) uniform readonly image2D denoisedImage;
layout(set = 0, binding = WB_DISPLAY_BIND_COST, rgba32f) uniform readonly image2D costImage;

layout(push_constant) uniform Push { DisplayPush pc; };

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

vec3 normalColor(vec3 n) { return dot(n, n) > 0.0 ? n * 0.5 + 0.5 : vec3(0.0); }

void main() {
  const vec2 uv = clamp((gl_FragCoord.xy - pc.viewRect.xy) / pc.viewRect.zw, vec2(0.0), vec2(0.9999));
  const ivec2 p = ivec2(uv * vec2(pc.imageSize));
  vec3 color;
  bool display = true;  // false: the view is data, shown without tonemapping
  const float lastBounce = max(pc.maxVertices - 1.0, 1.0);
  const bool costView = pc.view == WB_VIEW_COST || pc.view == WB_VIEW_INEFFICIENCY;
  if (pc.view == WB_VIEW_BEAUTY || pc.view == WB_VIEW_DROPPED || pc.view == WB_VIEW_NAN_SOURCE ||
      (costView && pc.costFull <= 0.0)) {
    if (uint(p.y) >= pc.tracedRows && pc.previewSize.x > 0u) {
      color = imageLoad(previewImage, ivec2(uv * vec2(pc.previewSize))).rgb;
    } else if (pc.view == WB_VIEW_BEAUTY && pc.denoiseSplit >= 0.0 && uv.x >= pc.denoiseSplit) {
      color = imageLoad(denoisedImage, p).rgb;
    } else {
      color = imageLoad(accumImage, p).rgb;
    }
    color = tonemap(color, pc.exposureScale, pc.tonemap);
    const float splitX = pc.viewRect.x + pc.denoiseSplit * pc.viewRect.z;
    if (pc.view == WB_VIEW_BEAUTY && pc.denoiseSplit > 0.0 && pc.denoiseSplit < 1.0 &&
        abs(gl_FragCoord.x - splitX) < 1.0)
      color = vec3(1.0, 0.8, 0.1);
    if (pc.view == WB_VIEW_DROPPED) {
      const float dropped = imageLoad(albedoImage, p).a;
      color = dropped > 0.0 ? vec3(1.0, 0.0, 1.0) : color * 0.25;
    } else if (pc.view == WB_VIEW_NAN_SOURCE) {
      const float bounce = imageLoad(statsImage, p).a;
      color = bounce < 1.0e29 ? heatRamp(bounce / lastBounce) : color * 0.25;
      display = bounce >= 1.0e29;
    } else if (costView) {
      color *= 0.25;  // no cost data (yet, or no shader clock): the panel says which
    }
  } else if (pc.view == WB_VIEW_ALBEDO) {
    color = imageLoad(albedoImage, p).rgb;
  } else if (pc.view == WB_VIEW_SHADING_NORMAL) {
    color = normalColor(imageLoad(normalImage, p).rgb);
    display = false;
  } else if (pc.view == WB_VIEW_GEOMETRIC_NORMAL) {
    color = normalColor(imageLoad(infoImage, p).rgb);
    display = false;
  } else if (pc.view == WB_VIEW_DEPTH) {
    const float d = imageLoad(normalImage, p).a;
    color = d < 0.0 ? vec3(0.1, 0.0, 0.15) : vec3(1.0 - d / (d + pc.sceneScale));
    display = false;
  } else if (pc.view == WB_VIEW_RR_END) {
    const vec4 s = imageLoad(statsImage, p);
    color = s.g > 0.0 ? heatRamp(s.b / s.g / lastBounce) : vec3(0.1, 0.0, 0.15);
    display = false;
  } else if (pc.view == WB_VIEW_COST) {
    const vec4 cost = imageLoad(costImage, p);
    color = heatRamp((pc.costMedian != 0u ? cost.a : cost.r) / pc.costFull);
    display = false;
  } else if (pc.view == WB_VIEW_INEFFICIENCY) {
    // Relative variance of one sample x its clocks: noisy and expensive at once (1 / efficiency).
    const float mean = dot(imageLoad(accumImage, p).rgb, vec3(0.2126, 0.7152, 0.0722));
    const float variance = max(imageLoad(statsImage, p).r - mean * mean, 0.0);
    const vec4 cost = imageLoad(costImage, p);
    const float v = mean > 0.0 ? variance / (mean * mean) * (pc.costMedian != 0u ? cost.a : cost.r) : 0.0;
    color = heatRamp(v / max(pc.inefficiencyFull, 1e-30));
    display = false;
  } else if (pc.view == WB_VIEW_VARIANCE) {
    // Relative standard deviation r of one sample, shown as r / (1 + r): 1 (as much noise as signal) is mid-scale,
    // a pixel with fireflies (a few samples many times the mean) goes to red.
    const float mean = dot(imageLoad(accumImage, p).rgb, vec3(0.2126, 0.7152, 0.0722));
    const float variance = max(imageLoad(statsImage, p).r - mean * mean, 0.0);
    const float r = mean > 0.0 ? sqrt(variance) / mean : 0.0;
    color = heatRamp(r / (1.0 + r));
    display = false;
  } else {
    const float vertices = imageLoad(infoImage, p).a;
    color = heatRamp(vertices / max(pc.maxVertices, 1.0));
    display = false;
  }
  // Data views are shown as stored values (no transfer curve): a normal of 0.5 shows as 50% grey.
  if (pc.encodeSrgb != 0u && display) color = linearToSrgb(color);
  if (pc.encodeSrgb == 0u && !display) color = pow(color, vec3(2.2));
  outColor = vec4(color, 1.0);
}
