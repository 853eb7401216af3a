#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
// The samples of one launch of several (raygen's sample slots) accumulated into the image in sample order, as raygen
// accumulates a launch of one: the same running average, NaN/Inf samples skipped (raygen counted them).
#include "../shared/bindings.h"
#include "../shared/pathtracer_types.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = WB_BIND_ACCUM, rgba32f) uniform image2D accumImage;
layout(set = 0, binding = WB_BIND_SAMPLE_SLOTS, scalar) readonly buffer SampleSlotBlock { vec4 sampleSlots[]; };
layout(push_constant, scalar) uniform ResolveBlock { ResolveConstants rc; };

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= rc.imageSize.x || pixel.y >= rc.imageSize.y) return;
  const ivec2 p = ivec2(pixel);
  vec4 acc = rc.firstSample == 0u ? vec4(0.0) : imageLoad(accumImage, p);
  for (uint s = 0u; s < rc.samples; ++s) {
    const vec3 radiance = sampleSlots[(s * rc.imageSize.y + pixel.y) * rc.imageSize.x + pixel.x].rgb;
    if (any(isnan(radiance)) || any(isinf(radiance))) continue;
    acc = vec4(mix(acc.rgb, radiance, 1.0 / (acc.a + 1.0)), acc.a + 1.0);
  }
  imageStore(accumImage, p, acc);
}
