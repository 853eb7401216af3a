// A finished sample into the accumulation, as raygen.rgen and the split's shadow launch (shadow_split.rgen) both
// finish one: a running mean per pixel, or with several samples per launch the sample's slot, which resolve.comp
// accumulates in sample order; with AOVs (WB_FLAG_AOV; the split's variant with WB_SPLIT_AOVS) the first hit's
// guides and the heat maps' running means.
#ifndef WB_PT_ACCUMULATE_GLSL
#define WB_PT_ACCUMULATE_GLSL

layout(set = 0, binding = WB_BIND_ACCUM, rgba32f) uniform image2D accumImage;
layout(set = 0, binding = WB_BIND_SAMPLE_SLOTS, scalar) writeonly buffer SampleSlotBlock { vec4 sampleSlots[]; };
layout(set = 0, binding = WB_BIND_AOV_ALBEDO, rgba16f) uniform image2D albedoImage;
layout(set = 0, binding = WB_BIND_AOV_NORMAL, rgba16f) uniform image2D normalImage;
layout(set = 0, binding = WB_BIND_AOV_INFO, rgba16f) uniform image2D infoImage;
layout(set = 0, binding = WB_BIND_AOV_STATS, rgba32f) uniform image2D statsImage;

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

// What a sample leaves in the AOV images besides its radiance: the first hit's albedo, shading normal, geometric
// normal and distance (-1: a miss), the path rays it traced, the bounce where Russian roulette ended it (-1: not
// ended so) and the first bounce whose contribution was NaN/Inf (WB_NO_NON_FINITE: none).
struct SampleAovs {
  vec3 albedo;
  float firstHitT;
  vec3 normal;
  float rays;
  vec3 geoNormal;
  float rrEndBounce;
  float nonFiniteBounce;
};

// The AOVs' running means over the samples after accumulateSample (`before`: what it returned). With AOVs a launch
// traces one sample per pixel (PathTracer::samplesPerLaunch).
void accumulateAovs(uvec2 pixel, vec3 radiance, float before, SampleAovs s) {
  const ivec2 p = ivec2(pixel);
  // Plain running averages over all samples (dropped ones count as 1 in the dropped fraction).
  const float w = 1.0 / float(pc.sampleIndex + 1u);
  const bool first = pc.sampleIndex == 0u;
  const vec4 a = first ? vec4(0.0) : imageLoad(albedoImage, p);
  const vec4 nn = first ? vec4(0.0) : imageLoad(normalImage, p);
  const vec4 info = first ? vec4(0.0) : imageLoad(infoImage, p);
  const float dropped = finite3(radiance) ? 0.0 : 1.0;
  imageStore(albedoImage, p, mix(a, vec4(s.albedo, dropped), w));
  imageStore(normalImage, p, mix(nn, vec4(s.normal, s.firstHitT), w));
  imageStore(infoImage, p, mix(info, vec4(s.geoNormal, s.rays), w));
  // The luminance^2 average follows the accumulation's (finite samples only); the rest all samples.
  const vec4 st = first ? vec4(0.0, 0.0, 0.0, WB_NO_NON_FINITE) : imageLoad(statsImage, p);
  const float lum = dot(radiance, vec3(0.2126, 0.7152, 0.0722));
  const vec2 rr = s.rrEndBounce >= 0.0 ? vec2(1.0, s.rrEndBounce) : vec2(0.0);
  const float lum2 = finite3(radiance) ? mix(st.r, lum * lum, 1.0 / (before + 1.0)) : st.r;
  imageStore(statsImage, p, vec4(lum2, mix(st.gb, rr, w), min(st.a, s.nonFiniteBounce)));
}

#if WB_SPLIT_SHADOWS
#ifndef WB_SPLIT_AOVS
#define WB_SPLIT_AOVS 0  // the split's variant without AOVs (PathTracer::splitsAovs)
#endif
// The split's record of a sample (SplitPathBlock, bindings.h): its radiance without the light samples left to the
// shadow launch and how many it left, then with AOVs its SampleAovs: the first hit's (stored at the first hit),
// then the path rays and the Russian-roulette and NaN/Inf bounces of the path's own contributions (stored at its
// end; the shadow launch takes the light samples' NaN/Inf bounces into the last).
uint splitRecord(uint record) { return record * (WB_SPLIT_AOVS != 0 ? WB_SPLIT_PATH_VEC4S_AOV : 1u); }

void storeSplitFirstHit(uint record, vec3 albedo, float firstHitT, vec3 normal, vec3 geoNormal) {
  const uint r = splitRecord(record);
  splitPaths[r + 1u] = vec4(albedo, firstHitT);
  splitPaths[r + 2u] = vec4(normal, 0.0);
  splitPaths[r + 3u] = vec4(geoNormal, 0.0);
}

void storeSplitPath(uint record, vec3 radiance, uint requests, float rays, float rrEndBounce, float nonFiniteBounce) {
  const uint r = splitRecord(record);
  splitPaths[r] = vec4(radiance, float(requests));
  if (WB_SPLIT_AOVS != 0) splitPaths[r + 4u] = vec4(rays, rrEndBounce, nonFiniteBounce, 0.0);
}

SampleAovs loadSplitAovs(uint record) {
  const uint r = splitRecord(record);
  SampleAovs s;
  const vec4 a = splitPaths[r + 1u], path = splitPaths[r + 4u];
  s.albedo = a.xyz;
  s.firstHitT = a.w;
  s.normal = splitPaths[r + 2u].xyz;
  s.geoNormal = splitPaths[r + 3u].xyz;
  s.rays = path.x;
  s.rrEndBounce = path.y;
  s.nonFiniteBounce = path.z;
  return s;
}
#endif

#endif
