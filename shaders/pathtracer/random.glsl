// Per-path sample streams (owen, Sobol + blue-noise rotation, or PCG), dimension layout in shared/random.h.
#ifndef WB_PT_RANDOM_GLSL
#define WB_PT_RANDOM_GLSL
#include "../shared/random.h"

// Private to each shader invocation: raygen and closest-hit each call initPathSampler() (globals do not travel
// between stages; only the payload does).
SamplerState gSampler;

void initPathSampler(uvec2 pixel, uint sampleIndex) {
  const uint mode = (pc.flags & WB_FLAG_SAMPLER_PCG) != 0u    ? WB_SAMPLER_PCG
                    : (pc.flags & WB_FLAG_SAMPLER_OWEN) != 0u ? WB_SAMPLER_OWEN
                                                               : WB_SAMPLER_SOBOL;
  gSampler = samplerInit(pixel, sampleIndex, pc.seed, mode);
}

// Dimensions 0-1: pixel jitter.
float pathSample(uint dim) { return samplerGet1D(gSampler, dim); }
// Dimension k (WB_DIM_*) of bounce b.
float pathSampleBounce(uint bounce, uint k) { return samplerGet1D(gSampler, sampleDimension(bounce, k)); }

#endif
