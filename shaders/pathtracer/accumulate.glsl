// A finished sample into the accumulation, as raygen.rgen and the split's shadow launch (shadow_split.rgen) both
// finish one: a running mean per pixel, or with several samples per launch the sample's slot, which resolve.comp
// accumulates in sample order.
#ifndef WB_PT_ACCUMULATE_GLSL
#define WB_PT_ACCUMULATE_GLSL

layout(set = 0, binding = WB_BIND_ACCUM, rgba32f) uniform image2D accumImage;
layout(set = 0, binding = WB_BIND_SAMPLE_SLOTS, scalar) writeonly buffer SampleSlotBlock { vec4 sampleSlots[]; };

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Accumulates `radiance` into the pixel and returns the samples the pixel held before (the accumulation's alpha);
// a NaN/Inf sample is counted for the host and dropped, the pixel keeping its count (a running mean that dropped
// samples do not bias). With several samples per launch the sample goes to its slot instead and 0 is returned.
float accumulateSample(uvec2 pixel, vec3 radiance) {
  if (gl_LaunchSizeEXT.z > 1u) {
    sampleSlots[(gl_LaunchIDEXT.z * pc.imageSize.y + pixel.y) * pc.imageSize.x + pixel.x] = vec4(radiance, 0.0);
    if (!finite3(radiance)) atomicAdd(counters.droppedSamples, 1u);
    return 0.0;
  }
  const ivec2 p = ivec2(pixel);
  const vec4 previous = pc.sampleIndex == 0u ? vec4(0.0) : imageLoad(accumImage, p);
  if (!finite3(radiance)) {
    atomicAdd(counters.droppedSamples, 1u);
    if (pc.sampleIndex == 0u) imageStore(accumImage, p, vec4(0.0));
  } else {
    imageStore(accumImage, p, vec4(mix(previous.rgb, radiance, 1.0 / (previous.a + 1.0)), previous.a + 1.0));
  }
  return previous.a;
}

#endif
