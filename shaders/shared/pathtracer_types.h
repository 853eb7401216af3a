// The path tracer's per-frame uniforms, push constants and counters, defined once for C++ and GLSL.
// Layouts are std430/scalar-compatible: vec3 members are always followed by a 4-byte scalar.
#ifndef WB_PATHTRACER_TYPES_H
#define WB_PATHTRACER_TYPES_H
#include "glsl_cpp.h"

// Push-constant flags.
#define WB_FLAG_SAMPLER_PCG 1u       // PCG random numbers instead of Sobol + blue noise
#define WB_FLAG_NO_NEE 2u            // disable next-event estimation (BRDF sampling only)
#define WB_FLAG_NO_BRDF_MIS 4u       // light sampling only for the environment (no MIS with BRDF)
#define WB_FLAG_NO_RR 8u             // Russian roulette off
#define WB_FLAG_AOV 16u              // write the AOV images (albedo, normals, depth, bounces, dropped samples)
#define WB_FLAG_SAMPLER_OWEN 32u     // Owen-scrambled Sobol (shared/random.h) instead of Sobol + blue noise
// Directional lights the generic build shades (scene::kGenericMaxLights); the host defines a larger value for a
// scene with more.
#ifndef WB_GENERIC_MAX_LIGHTS
#define WB_GENERIC_MAX_LIGHTS 8u
#endif
// The shader clock a cost variant reads (VK_KHR_shader_clock; the host defines WB_CLOCK to one of them).
#define WB_CLOCK_NONE 0u
#define WB_CLOCK_SUBGROUP 1u  // GL_ARB_shader_clock: the subgroup's clock (GPU: the multiprocessor's cycles)
#define WB_CLOCK_DEVICE 2u    // GL_EXT_shader_realtime_clock: the device's clock
// The a channel of WB_BIND_AOV_STATS where no sample became NaN/Inf.
#define WB_NO_NON_FINITE 1.0e30

WB_NAMESPACE_BEGIN

// Per-frame uniforms (binding WB_BIND_FRAME).
struct FrameUniforms {
  mat4 viewInverse;
  mat4 projInverse;
  vec4 envColor;  // rgb constant environment radiance (used when envMapPresent == 0), a unused
  uint lightCount;
  uint envMapPresent;
  uint envWidth;
  uint envHeight;
  float envIntensity;
  float envRotation;  // radians about +Y
  float envTotalWeight;  // sum of the alias table's unnormalised weights
  float sceneScale;  // scene bounding radius (for debug views only; never an epsilon)
  uint emitterCount;  // emissive triangles in WB_BIND_EMITTERS
  float emitterTotalPower;  // sum over emitters of luminance(emissive factor) * world area
  float envSelectProbability;  // NEE picks the environment with this probability, emitters otherwise
  uint reflectorCount;  // glossy reflectors in WB_BIND_REFLECTORS the continuation rays may be guided towards
};

// Per-dispatch push constants (at most 128 bytes).
struct PushConstants {
  uint sampleIndex;  // index of the sample being accumulated (0 = overwrite)
  uint maxBounces;
  uint rrStart;
  float rrMin;
  float rrMax;
  uint flags;
  uint seed;
  uint debugView;
  uvec2 tileOffset;  // first pixel of the traced region
  uvec2 imageSize;   // full accumulation image size
  float rrExponent;  // Russian roulette survival = clamp(max throughput ^ rrExponent, rrMin, rrMax)
  uint splitSlots;   // WB_SPLIT_SHADOWS: shadow requests a sample may leave for the shadow launch
};

// The resolve pass's push constants (pathtracer/resolve.comp): the samples of one launch, in order.
struct ResolveConstants {
  uvec2 imageSize;
  uint firstSample;  // the sample index of slot 0 (0: the accumulation restarts)
  uint samples;      // slots to accumulate
};

// Counters the host reads back.
struct Counters {
  uint droppedSamples;  // NaN/Inf samples not accumulated
  uint rayCount;        // all rays traced (approximate, atomics per pixel)
  uint shadowRayCount;
  uint pathCount;
  uint isolateNext;  // the next pixel of the lane-isolated cost variant's queue (raygen.rgen; reset per launch)
};

WB_NAMESPACE_END

#endif
