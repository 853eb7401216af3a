// Per-path sample streams. Dimensions: 0-1 pixel jitter, then WB_DIMS_PER_BOUNCE per bounce.
#ifndef WB_PT_RANDOM_GLSL
#define WB_PT_RANDOM_GLSL

#define WB_DIMS_PER_BOUNCE 8u
#define WB_DIM_LOBE 0u
#define WB_DIM_BRDF_U 1u
#define WB_DIM_BRDF_V 2u
#define WB_DIM_LIGHT_U 3u
#define WB_DIM_LIGHT_V 4u
#define WB_DIM_LIGHT_CHOICE 5u
#define WB_DIM_RR 6u
#define WB_DIM_ALPHA 7u

uvec2 gSamplePixel;
uint gSampleIndex;

uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

void initPathSampler(uvec2 pixel, uint sampleIndex) {
  gSamplePixel = pixel;
  gSampleIndex = sampleIndex;
}

float pathSample(uint dim) {
  uint h = pcgHash(gSamplePixel.x ^ pcgHash(gSamplePixel.y ^ pcgHash(gSampleIndex ^ pcgHash(dim ^ pc.seed))));
  return min(float(h >> 8) * (1.0 / 16777216.0), 0.99999994);
}

float pathSampleBounce(uint bounce, uint dim) { return pathSample(2u + bounce * WB_DIMS_PER_BOUNCE + dim); }

#endif
