// Random numbers for the path tracer, shared by shaders and CPU tests. Three samplers (WB_SAMPLER_*):
//  - sobol: a Sobol sequence with per-pixel Cranley-Patterson rotation from a 128x128 blue-noise texture;
//  - pcg:   PCG hashing (independent uniform numbers, the comparison mode);
//  - owen:  Owen-scrambled Sobol points in the style of Burley 2020, "Practical Hash-based Owen Scrambling"
//           (JCGT 9(4)): each group of dimensions a path vertex uses together (a "set": pixel jitter, BRDF lobe +
//           direction, light choice + light sample, Russian roulette, alpha) is a low-dimensional Sobol point
//           (Sobol dimensions 0..3) of a per-pixel, per-set shuffled index, and every coordinate is nested-uniform
//           (Owen) scrambled with a per-pixel, per-set, per-coordinate seed. The shuffle decorrelates the sets
//           ("padding"); within a set every aligned block of 2^m samples stays a scrambled (t,m,s)-net, so each 2D
//           pair (Sobol dimensions 0 and 1) is stratified into 2^m elementary intervals of every shape at every
//           power of two, progressively. Every pixel and seed is an independent randomisation.
//
// One source of random numbers for every renderer: the path tracer's samplers below, and hashStreamNext, a
// sequential stream that needs no tables (the hybrid modes' shadow and AO rays). Both end in uintToUnitFloat.
//
// Table access (GLSL cannot pass buffers to functions): before including this header a shader defines
//   #define WB_SOBOL_DIR(dim, bit)  sobolBuffer.dirs[(dim) * 32u + (bit)]          // uint, binding WB_BIND_SOBOL
//   #define WB_BLUE_NOISE(x, y)     wbUnpackBlueNoise(blueNoiseBuffer.texels[(y) * 128u + (x)])
//                                                                      // vec2 in [0,1), binding WB_BIND_BLUE_NOISE
// (wbUnpackBlueNoise is defined below, so the macro may use it), or defines WB_RANDOM_NO_TABLES for the table-free
// part alone (uintToUnitFloat, pcgNext, hashStreamNext). In C++ the defaults read the thread-local pointers
// wb::gpu::gSobolDirections / gBlueNoise (set them, e.g. with the vectors from sobolDirectionNumbers() and
// blueNoise128(), before calling the sampler).
//
// Dimension layout (WB_DIM_* below), one path sample = one sample index (the accumulation sample index):
//   0, 1                     pixel jitter (x, y)
//   2 + b * 10 + k, bounce b = 0 .. (bounce 0 = the camera ray's first hit):
//     k = 0  BRDF lobe choice              k = 1, 2  BRDF direction        (brdfSample u = (k0, k1, k2))
//     k = 3  light choice (env vs lights)  k = 4,5,6 light / env sample     (k4 picks the emitter or env texel,
//                                                                            (k5, k6) the point)
//     k = 7  Russian roulette              k = 8  alpha (stochastic transparency)   k = 9  spare
// sobol: dimensions >= WB_SOBOL_DIMS (bounces past WB_SOBOL_MAX_BOUNCES) fall back to PCG hashing. Pairs (2j, 2j+1)
// share one blue-noise texel (its two channels); each pair reads the texture at its own toroidal offset, so the
// rotations of different dimensions are decorrelated. The temporal scramble adds seed * 0x9E3779B9 (golden ratio,
// 0.32 fixed point) plus a per-dimension hash of the seed to the rotation: pass a value that is constant during an
// accumulation (e.g. PushConstants.seed) to keep the Sobol stratification across the sample indices; change it to
// decorrelate accumulations (different seeds give independent estimates), or pass the frame number for animated
// 1-spp noise.
// owen: sets per bounce (WB_OWEN_SET_OF / WB_OWEN_COORD_OF): {k1, k2, k0} -> Sobol dimensions (0, 1, 2) (the BRDF
// direction gets the best-stratified pair), {k5, k6, k4, k3} -> (0, 1, 2, 3) (the point on the light likewise),
// and k7, k8, k9 one set each (dimension 0: a stratified 1D sequence). No bounce limit, no blue noise.
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
#define WB_SAMPLER_SOBOL 0u
#define WB_SAMPLER_PCG 1u
#define WB_SAMPLER_OWEN 2u
// owen: set (3 bits) and Sobol dimension (1 bit) of each per-bounce offset k = 0..9, packed k-major.
#define WB_OWEN_SETS_PER_BOUNCE 8u
#define WB_OWEN_SET_OF 0x3eb23401u    // k: 0 1 2 3 4 5 6 7 8 9 -> set 1 0 0 2 3 4 4 5 6 7
#define WB_OWEN_COORD_OF 0x044u       // k: 0 1 2 3 4 5 6 7 8 9 -> dim 0 0 1 0 0 0 1 0 0 0

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

// A sequential stream of uniform numbers in [0,1) by hash chaining (state = pcgHash(state)): seed the state with a
// hash of what the numbers should be independent over (pixel, frame, seed).
WB_FN float hashStreamNext(INOUT(uint) state) {
  state = pcgHash(state);
  return uintToUnitFloat(state);
}

// Packed blue-noise texel (low 16 bits: channel 0, high 16 bits: channel 1) -> two values in [0,1).
WB_FN vec2 wbUnpackBlueNoise(uint v) {
  return vec2(float(v & 0xffffu) * (1.0f / 65536.0f), float(v >> 16u) * (1.0f / 65536.0f));
}

WB_NAMESPACE_END

#if defined(__cplusplus) || !defined(WB_RANDOM_NO_TABLES)
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

// Owen scrambling: a nested uniform scramble of a 32-bit fixed-point value (every bit flipped by a hash of the
// bits above it), computed as a hash of the bit-reversed value whose bit i depends only on bits 0..i: the
// permutation of Vegdahl 2021 ("Building a Better LK Hash"), an improvement of Laine and Karras 2011's that
// Burley 2020 uses (the one Cycles uses). The seed should be well mixed (a pcgHash output).
WB_FN uint owenPermutation(uint x, uint seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16u) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}
WB_FN uint nestedUniformScramble(uint x, uint seed) { return bitfieldReverse(owenPermutation(bitfieldReverse(x), seed)); }

// owen: set number and Sobol dimension (0..3) of sampler dimension dim (layout in the header comment).
WB_FN uint owenSet(uint dim) {
  if (dim < WB_DIM_BOUNCE_BASE) return 0u;
  uint d = dim - WB_DIM_BOUNCE_BASE;
  uint bounce = d / WB_DIMS_PER_BOUNCE;
  uint k = d - bounce * WB_DIMS_PER_BOUNCE;
  return 1u + bounce * WB_OWEN_SETS_PER_BOUNCE + ((WB_OWEN_SET_OF >> (3u * k)) & 7u);
}
WB_FN uint owenCoordinate(uint dim) {
  if (dim < WB_DIM_BOUNCE_BASE) return dim;
  uint k = (dim - WB_DIM_BOUNCE_BASE) % WB_DIMS_PER_BOUNCE;
  return (WB_OWEN_COORD_OF >> k) & 1u;
}

// Sobol dimension 1 (primitive polynomial x + 1, the Pascal matrix mod 2) of the bit-reversed index r, as 32-bit
// fixed point: over GF(2) the Pascal matrix maps the index's bits, read as a polynomial A(t), to those of A(t + 1),
// and (t + 1)^(2^k) = t^(2^k) + 1 lets that shift run as five shift-XORs (bit-reversed order: bit 31 - j of r is
// bit j of the index). Equals sobolBits(index, 1) of the direction-number table (checked by a test).
WB_FN uint sobolDim1Reversed(uint r) {
  r ^= (r << 1u) & 0xaaaaaaaau;
  r ^= (r << 2u) & 0xccccccccu;
  r ^= (r << 4u) & 0xf0f0f0f0u;
  r ^= (r << 8u) & 0xff00ff00u;
  r ^= (r << 16u) & 0xffff0000u;
  return r;
}

// One owen value: coordinate `coord` (0 or 1: Sobol dimension 0 or 1) of the set's shuffled sample index,
// Owen-scrambled. pixelSeed is a hash of the pixel and the seed, reversedIndex the bit-reversed sample index
// (SamplerState.owenBase / .reversedIndex). The shuffle is a nested uniform scramble of the index's low 16 bits
// (bit i flipped by a hash of the bits above i), computed in the bit-reversed domain: for a fixed upper half it
// permutes [0, 2^16), and the first 2^m indices (m <= 16) land on one aligned block of 2^m Sobol indices, a
// (0,m,2)-net like the first block. Sobol dimension 0 is the reversed index itself, dimension 1 its Pascal
// transform: no table, no loop.
WB_FN uint owenBits(uint pixelSeed, uint reversedIndex, uint set, uint coord) {
  uint setSeed = pcgHash(pixelSeed + set * 0x9e3779b9u);
  uint reversed = (owenPermutation(reversedIndex, setSeed) & 0xffff0000u) | (reversedIndex & 0x0000ffffu);
  uint bits = coord == 0u ? reversed : sobolDim1Reversed(reversed);
  return nestedUniformScramble(bits, pcgHash(setSeed ^ (coord * 0x68bc21ebu + 0x02e5be93u)));
}

// Per-path sampler state: which pixel and sample this is, and the mode.
struct SamplerState {
  uvec2 pixel;
  uint sampleIndex;  // sample index (accumulation sample index)
  uint seed;         // temporal scramble / PCG seed
  uint pcgBase;      // per-path hash (PCG mode and dimensions past WB_SOBOL_DIMS)
  uint mode;         // WB_SAMPLER_*
  uint owenBase;     // per-pixel hash of pixel and seed (owen)
  uint reversedIndex;  // bitfieldReverse(sampleIndex) (owen)
};

WB_FN SamplerState samplerInit(uvec2 pixel, uint sampleIndex, uint seed, uint mode) {
  SamplerState s;
  s.pixel = pixel;
  s.sampleIndex = sampleIndex;
  s.seed = seed;
  s.pcgBase = pcgHash(pixel.x + pcgHash(pixel.y + pcgHash(sampleIndex + pcgHash(seed))));
  s.mode = mode;
  s.owenBase = pcgHash(pixel.x ^ pcgHash(pixel.y ^ pcgHash(seed ^ 0x6f77656eu)));
  s.reversedIndex = bitfieldReverse(sampleIndex);
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
  if (s.mode == WB_SAMPLER_OWEN) return uintToUnitFloat(owenBits(s.owenBase, s.reversedIndex, owenSet(dim), owenCoordinate(dim)));
  if (s.mode == WB_SAMPLER_PCG || dim >= WB_SOBOL_DIMS) return uintToUnitFloat(pcgHash(s.pcgBase + pcgHash(dim)));
  return uintToUnitFloat(sobolBits(s.sampleIndex, dim) + blueNoiseRotationBits(s.pixel, dim, s.seed));
}
WB_FN vec2 samplerGet2D(SamplerState s, uint dim) {
  return vec2(samplerGet1D(s, dim), samplerGet1D(s, dim + 1u));
}
WB_FN vec3 samplerGet3D(SamplerState s, uint dim) {
  return vec3(samplerGet1D(s, dim), samplerGet1D(s, dim + 1u), samplerGet1D(s, dim + 2u));
}

WB_NAMESPACE_END

#endif  // the samplers (tables)

#endif
