#version 460
#extension GL_GOOGLE_include_directive : require
// The last pass with DenoisePush::window: each output pixel (final.comp left it in the filter plane it did not
// read) times its window's gain (gain.comp), interpolated bilinearly between the centres of the groups so that
// no group's edge shows, into the output image.
#include "common.glsl"

layout(set = 0, binding = WB_DENOISE_BIND_OUTPUT, rgba32f) uniform writeonly image2D outputImage;

vec3 gainAt(ivec2 g, ivec2 groups) {
  const ivec2 q = clamp(g, ivec2(0), groups - 1);
  return gain[q.y * groups.x + q.x].rgb;
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(pc.imageSize.x) || p.y >= int(pc.imageSize.y)) return;
  const ivec2 groups = ivec2(groupCount());
  const vec2 u = (vec2(p) + 0.5) / float(WB_DENOISE_GROUP_SIZE) - 0.5;
  const ivec2 g = ivec2(floor(u));
  const vec2 f = u - floor(u);
  const vec3 scale = mix(mix(gainAt(g, groups), gainAt(g + ivec2(1, 0), groups), f.x),
                         mix(gainAt(g + ivec2(0, 1), groups), gainAt(g + ivec2(1, 1), groups), f.x), f.y);
  const vec4 v = filtered[(pc.source ^ 1u) * planeSize() + pixelIndex(p)];
  imageStore(outputImage, p, vec4(v.rgb * scale, v.a));
}
