// What the denoiser's passes share: push constants, luminance, the albedo used to demodulate, the unit normal
// the first pass stores, where a pixel is in the buffers, and the edge-stopping weights of the a-trous filter
// (SVGF: Schied et al. 2017).
#ifndef WB_DENOISE_COMMON_GLSL
#define WB_DENOISE_COMMON_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#include "../shared/denoise_types.h"

layout(local_size_x = WB_DENOISE_GROUP_SIZE, local_size_y = WB_DENOISE_GROUP_SIZE) in;
layout(push_constant) uniform PushBlock { DenoisePush pc; };

// The denoiser's buffers, by the addresses in pc.buffers (denoise_types.h says what each holds), under the names
// the passes index them by.
layout(buffer_reference, std430, buffer_reference_align = 16) buffer DenoiseVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer DenoiseFloats { float v[]; };
#define geometry DenoiseVec4s(pc.buffers.geometry).v
#define filtered DenoiseVec4s(pc.buffers.filtered).v
#define gradient DenoiseFloats(pc.buffers.gradient).v
#define handover DenoiseVec4s(pc.buffers.handover).v
#define bias DenoiseFloats(pc.buffers.bias).v
#define tiles DenoiseVec4s(pc.buffers.tiles).v
#define gain DenoiseVec4s(pc.buffers.gain).v

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The albedo radiance is divided by before filtering and multiplied by after: the first-hit base colour,
// floored so that dark albedo does not amplify noise without bound; black (emitters, misses) is not demodulated.
vec3 demodulationAlbedo(vec3 albedo) {
  return max(albedo.r, max(albedo.g, albedo.b)) < 0.02 ? vec3(1.0) : max(albedo, vec3(0.02));
}

// The first-hit normal the edge-stopping weights compare: unit length; (0, 0, 0) for a miss, whose depth (< 0)
// is what the weights test.
vec3 unitNormal(vec3 n) { return dot(n, n) > 0.0 ? normalize(n) : vec3(0.0); }

bool insideImage(ivec2 q) {
  return q.x >= 0 && q.y >= 0 && q.x < int(pc.imageSize.x) && q.y < int(min(pc.rows, pc.imageSize.y));
}

// Where pixel q is in the denoiser's buffers, and how many elements one plane of them holds.
uint pixelIndex(ivec2 q) { return uint(q.y) * pc.imageSize.x + uint(q.x); }
uint planeSize() { return pc.imageSize.x * pc.imageSize.y; }
// The workgroups of final.comp over the whole image (its dispatch).
uvec2 groupCount() { return (pc.imageSize + uint(WB_DENOISE_GROUP_SIZE - 1)) / uint(WB_DENOISE_GROUP_SIZE); }

// The normals' part of the edge-stopping weight: their cosine to the power sigmaNormal; `squaring` (a constant
// at each call: the caller has checked sigmaNormal == 128) by squaring, with no transcendental function per tap.
// A caller branches once per pixel on sigmaNormal around its whole loop of taps, with a loop for each case, so
// that the compiler cannot flatten a per-tap branch into computing both sides (a CPU driver runs every lane
// of a vector through both sides of a flattened branch).
float normalWeight(vec3 nP, vec3 nQ, const bool squaring) {
  float c = max(dot(nP, nQ), 0.0);
  if (!squaring) return pow(c, pc.sigmaNormal);
  for (int i = 0; i < 7; ++i) c *= c;
  return c;
}

// The depths' part, as the exponent of exp(-e) (a caller adds other exponents and calls exp once): the
// difference of the depths against the change the depth gradient predicts over the taps' distance.
float depthExponent(float zP, float gradientP, float zQ, float distance) {
  const float expected = pc.sigmaDepth * gradientP * distance + 1.0e-3 * zP;
  return abs(zP - zQ) / expected;
}

// The geometric part of the edge-stopping weight between a pixel p and a tap q `distance` pixels away: normals
// and depths (geometry: the buffer's normal xyz and depth). A miss only meets misses.
float geometryWeight(vec4 geometryP, float gradientP, vec4 geometryQ, float distance, const bool squaring) {
  const bool missP = geometryP.w < 0.0, missQ = geometryQ.w < 0.0;
  if (missP || missQ) return missP && missQ ? 1.0 : 0.0;
  return normalWeight(geometryP.xyz, geometryQ.xyz, squaring) *
         exp(-depthExponent(geometryP.w, gradientP, geometryQ.w, distance));
}

// The a-trous kernel's weight of tap i (-1..1).
float kernelWeight(int i) { return i == 0 ? WB_DENOISE_KERNEL_CENTER : WB_DENOISE_KERNEL_SIDE; }

#endif
