// Random numbers for the path tracer, shared by shaders and CPU tests: PCG hashing (comparison mode) and a Sobol
// sequence with per-pixel Cranley-Patterson rotation from a 128x128 blue-noise texture.
//
// Table access (GLSL cannot pass buffers to functions): before including this header a shader defines
//   #define WB_SOBOL_DIR(dim, bit)  sobolBuffer.dirs[(dim) * 32u + (bit)]          // uint, binding WB_BIND_SOBOL
//   #define WB_BLUE_NOISE(x, y)     wbUnpackBlueNoise(blueNoiseBuffer.texels[(y) * 128u + (x)])
//                                                                      // vec2 in [0,1), binding WB_BIND_BLUE_NOISE
// (wbUnpackBlueNoise is defined below, so the macro may use it). In C++ the defaults read the thread-local pointers
// wb::gpu::gSobolDirections / gBlueNoise (set them, e.g. with the vectors from sobolDirectionNumbers() and
// blueNoise128(), before calling the sampler).
//
// Sobol dimension layout (WB_DIM_* below), one path sample = one Sobol index (the accumulation sample index):
//   0, 1                     pixel jitter (x, y)
//   2 + b * 10 + k, bounce b = 0 .. WB_SOBOL_MAX_BOUNCES - 1 (bounce 0 = the camera ray's first hit):
//     k = 0  BRDF lobe choice              k = 1, 2  BRDF direction        (brdfSample u = (k0, k1, k2))
//     k = 3  light choice (env vs lights)  k = 4,5,6 light / env sample     (envSample u = (k4, k5, k6))
//     k = 7  Russian roulette              k = 8  alpha (stochastic transparency)   k = 9  spare
//   Dimensions >= WB_SOBOL_DIMS (deeper bounces) fall back to PCG hashing.
// Pairs (2j, 2j+1) share one blue-noise texel (its two channels); each pair reads the texture at its own
// toroidal offset, so the rotations of different dimensions are decorrelated.
// The temporal scramble adds seed * 0x9E3779B9 (golden ratio, 0.32 fixed point) plus a per-dimension hash of the
// seed to the rotation: pass a value that is constant during an accumulation (e.g. PushConstants.seed) to keep the
// Sobol stratification across the sample indices; change it to decorrelate accumulations (different seeds give
// independent estimates), or pass the frame number for animated 1-spp noise.
#ifndef WB_RANDOM_H
#define WB_RANDOM_H
#include "hash.h"
#include "sampling_math.h"

#define WB_DIMS_PER_BOUNCE 10u
#define WB_SOBOL_MAX_BOUNCES 16u
#define WB_SOBOL_DIMS 162u  // 2 + WB_DIMS_PER_BOUNCE * WB_SOBOL_MAX_BOUNCES; direction-number buffer holds this many
#define WB_DIM_PIXEL 0u
#define WB_DIM_BOUNCE_BASE 2u
#define WB_DIM_LOBE 0u
#define WB_DIM_BRDF 1u
#define WB_DIM_LIGHT_CHOICE 3u
#define WB_DIM_LIGHT 4u
#define WB_DIM_RR 7u
#define WB_DIM_ALPHA 8u
#define WB_DIM_SPARE 9u
#define WB_BLUE_NOISE_SIZE 128u

WB_NAMESPACE_BEGIN

#ifdef __cplusplus
inline thread_local const uint* gSobolDirections = nullptr;  // [dim * 32 + bit], WB_SOBOL_DIMS dims
inline thread_local const uint* gBlueNoise = nullptr;        // [y * 128 + x], packed as WB_BIND_BLUE_NOISE
#endif

// First dimension used by bounce b for the quantity at offset k (WB_DIM_LOBE ...).
WB_FN uint sampleDimension(uint bounce, uint k) { return WB_DIM_BOUNCE_BASE + bounce * WB_DIMS_PER_BOUNCE + k; }

// 32 random bits -> float in [0,1) (strictly below 1: uses the top 24 bits).
WB_FN float uintToUnitFloat(uint x) { return float(x >> 8u) * (1.0f / 16777216.0f); }

// PCG-RXS-M-XS 32-bit generator step (state advances by the PCG LCG): a sequential RNG when one is needed.
WB_FN uint pcgNext(INOUT(uint) state) {
  uint s = state;
  state = state * 747796405u + 2891336453u;
  uint word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
  return (word >> 22u) ^ word;
}
WB_FN float pcgNextFloat(INOUT(uint) state) { return uintToUnitFloat(pcgNext(state)); }

// Packed blue-noise texel (low 16 bits: channel 0, high 16 bits: channel 1) -> two values in [0,1).
WB_FN vec2 wbUnpackBlueNoise(uint v) {
  return vec2(float(v & 0xffffu) * (1.0f / 65536.0f), float(v >> 16u) * (1.0f / 65536.0f));
}

WB_NAMESPACE_END

#ifdef __cplusplus
#ifndef WB_SOBOL_DIR
#define WB_SOBOL_DIR(dim, bit) (::wb::gpu::gSobolDirections[(dim) * 32u + (bit)])
#endif
#ifndef WB_BLUE_NOISE
#define WB_BLUE_NOISE(x, y) (::wb::gpu::wbUnpackBlueNoise(::wb::gpu::gBlueNoise[(y) * 128u + (x)]))
#endif
#else
#ifndef WB_SOBOL_DIR
#error "define WB_SOBOL_DIR(dim, bit) (a uint from the Sobol direction-number buffer) before including random.h"
#endif
#ifndef WB_BLUE_NOISE
#error "define WB_BLUE_NOISE(x, y) (vec2 in [0,1) from the 128x128 blue-noise buffer) before including random.h"
#endif
#endif

WB_NAMESPACE_BEGIN

// Unscrambled Sobol point of the sequence, 32-bit fixed point: XOR of the direction numbers of the set bits.
WB_FN uint sobolBits(uint index, uint dim) {
  uint r = 0u;
  uint i = index;
  uint bit = 0u;
  while (i != 0u) {
    if ((i & 1u) != 0u) r ^= WB_SOBOL_DIR(dim, bit);
    i = i >> 1u;
    bit = bit + 1u;
  }
  return r;
}
WB_FN float sobolSample(uint index, uint dim) { return uintToUnitFloat(sobolBits(index, dim)); }

// Owen scrambling (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)): nested uniform scramble via the
// Laine-Karras permutation of the bit-reversed value. Optional alternative to the blue-noise rotation.
WB_FN uint laineKarrasPermutation(uint x, uint seed) {
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return x;
}
WB_FN uint nestedUniformScramble(uint x, uint seed) {
  return bitfieldReverse(laineKarrasPermutation(bitfieldReverse(x), seed));
}
WB_FN float sobolOwenSample(uint index, uint dim, uint seed) {
  return uintToUnitFloat(nestedUniformScramble(sobolBits(index, dim), pcgHash(seed ^ pcgHash(dim))));
}

// Per-path sampler state: which pixel and sample this is, and the mode.
struct SamplerState {
  uvec2 pixel;
  uint sampleIndex;  // Sobol index (accumulation sample index)
  uint seed;         // temporal scramble / PCG seed
  uint pcgBase;      // per-path hash (PCG mode and dimensions past WB_SOBOL_DIMS)
  uint usePcg;       // 1: PCG hashing only (WB_FLAG_SAMPLER_PCG)
};

WB_FN SamplerState samplerInit(uvec2 pixel, uint sampleIndex, uint seed, bool usePcg) {
  SamplerState s;
  s.pixel = pixel;
  s.sampleIndex = sampleIndex;
  s.seed = seed;
  s.pcgBase = pcgHash(pixel.x + pcgHash(pixel.y + pcgHash(sampleIndex + pcgHash(seed))));
  s.usePcg = usePcg ? 1u : 0u;
  return s;
}

// Blue-noise Cranley-Patterson rotation of dimension dim for this pixel, 32-bit fixed point.
WB_FN uint blueNoiseRotationBits(uvec2 pixel, uint dim, uint seed) {
  uint pair = dim >> 1u;
  // R2-sequence toroidal offsets per dimension pair (0.7548776662, 0.5698402910 in 0.32 fixed point).
  uint ox = (pair * 3242174889u) >> 25u;
  uint oy = (pair * 2447445414u) >> 25u;
  vec2 bn = WB_BLUE_NOISE((pixel.x + ox) & (WB_BLUE_NOISE_SIZE - 1u), (pixel.y + oy) & (WB_BLUE_NOISE_SIZE - 1u));
  float c = (dim & 1u) == 0u ? bn.x : bn.y;
  // Temporal scramble: the golden-ratio multiple of the seed, plus a per-dimension hash of it (seed 0: neither), so
  // accumulations with different seeds are independent estimates rather than one shift applied to every dimension.
  return uint(c * 4294967040.0f) + seed * 2654435769u + (seed == 0u ? 0u : pcgHash(seed ^ pcgHash(dim + 0x9E3779B9u)));
}

// One sample value in [0,1) (strictly below 1) of dimension dim.
WB_FN float samplerGet1D(SamplerState s, uint dim) {
  if (s.usePcg != 0u || dim >= WB_SOBOL_DIMS) return uintToUnitFloat(pcgHash(s.pcgBase + pcgHash(dim)));
  return uintToUnitFloat(sobolBits(s.sampleIndex, dim) + blueNoiseRotationBits(s.pixel, dim, s.seed));
}
WB_FN vec2 samplerGet2D(SamplerState s, uint dim) {
  return vec2(samplerGet1D(s, dim), samplerGet1D(s, dim + 1u));
}
WB_FN vec3 samplerGet3D(SamplerState s, uint dim) {
  return vec3(samplerGet1D(s, dim), samplerGet1D(s, dim + 1u), samplerGet1D(s, dim + 2u));
}

WB_NAMESPACE_END

#endif
