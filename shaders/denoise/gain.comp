#version 460
#extension GL_GOOGLE_include_directive : require
// Where the output's radiance is made the raw image's over windows (DenoisePush::window), per 8x8 group of
// final.comp (its sums in `tiles`), in two phases (DenoisePush::step). The filter loses energy where it removes
// fireflies (a firefly's pixel trusts the filter while its calm neighbours keep their raw means); each group's
// deficit, raw minus output, goes back to the groups in its window (WB_DENOISE_WINDOW_GROUPS either side) in
// proportion to their output:
//   phase 0: c_j = (raw_j - output_j) / (the output summed over j's window), into tiles[2j];
//   phase 1: gain_g = 1 + sum of c_j over g's window (the windows are symmetric: g is in j's window where j is
//            in g's), into gain[g].
// Each group's output times its gain sums, over the image, to the raw radiance (per channel; exactly where no gain
// is clamped at 0): only the distribution within a window is the filter's. scale.comp applies the gains,
// interpolated between group centres, which keeps the sum to ~2e-4 (DenoiserFixture.TheWindowedGainKeepsThe...).
// One invocation per group.
#include "common.glsl"

void main() {
  const ivec2 groups = ivec2(groupCount());
  const ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (g.x >= groups.x || g.y >= groups.y) return;
  const uint i = uint(g.y * groups.x + g.x);
  const uint part = pc.step == 0u ? 1u : 0u;  // phase 0 sums the outputs, phase 1 the shares c_j
  vec3 sum = vec3(0.0);
  for (int y = -WB_DENOISE_WINDOW_GROUPS; y <= WB_DENOISE_WINDOW_GROUPS; ++y) {
    for (int x = -WB_DENOISE_WINDOW_GROUPS; x <= WB_DENOISE_WINDOW_GROUPS; ++x) {
      const ivec2 q = g + ivec2(x, y);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, groups))) continue;
      sum += tiles[2u * uint(q.y * groups.x + q.x) + part].rgb;
    }
  }
  if (pc.step == 0u) {
    // Only this group's own raw sum is read and overwritten here; the others read outputs.
    const vec3 deficit = tiles[2u * i].rgb - tiles[2u * i + 1u].rgb;
    tiles[2u * i] = vec4(mix(vec3(0.0), deficit / max(sum, vec3(1.0e-30)), greaterThan(sum, vec3(0.0))), 0.0);
  } else {
    gain[i] = vec4(max(vec3(1.0) + sum, vec3(0.0)), 0.0);
  }
}
