// Resources and helpers shared by every stage of the path tracer (bindings come from shared/bindings.h).
#ifndef WB_PT_COMMON_GLSL
#define WB_PT_COMMON_GLSL

#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
// WB_CLOCK (the host defines it in the cost and inspecting variants where the device has VK_KHR_shader_clock):
// 1 the subgroup clock, 2 the device clock (WB_CLOCK_* in shared/pathtracer_types.h).
#ifndef WB_CLOCK
#define WB_CLOCK 0
#endif
#if WB_CLOCK == 1
#extension GL_ARB_shader_clock : require
#elif WB_CLOCK == 2
#extension GL_EXT_shader_realtime_clock : require
#endif

#include "../shared/bindings.h"
#include "../shared/pathtracer_types.h"

// Scene-driven specialisation (src/scene/features.h): the host defines WB_SPECIALIZED and the WB_HAS_* / WB_LIGHT_COUNT
// / WB_ENV_MODE values for what the scene uses; without them (or with WB_GENERIC) every feature is compiled in.
#ifndef WB_SPECIALIZED
#define WB_HAS_ALPHA_MASK 1
#define WB_HAS_ALPHA_BLEND 1
#define WB_HAS_NORMAL_MAPS 1
#define WB_HAS_EMISSIVE 1
#define WB_HAS_TEXTURES 1
#define WB_HAS_SPECULAR 1
#define WB_LIGHT_COUNT min(frame.lightCount, WB_GENERIC_MAX_LIGHTS)
#define WB_ENV_MODE WB_ENV_MAP
#endif
// WB_CPU_DEVICE=1 (the host sets it for CPU devices, lavapipe): code shaped for a driver that JIT-compiles the
// whole pipeline at its first trace after every change, every inlined copy of a function included: repeated calls
// become loops there. GPUs get the straight-line code they run faster.
#ifndef WB_CPU_DEVICE
#define WB_CPU_DEVICE 0
#endif
// Raygen traces the same number of shadow iterations at every vertex (raygen.rgen), so that a SIMD group's
// threads trace path rays and shadow rays in the same iterations (docs/bench/roofline.md; 0: as many as the
// vertex asked for).
#ifndef WB_SHADOW_LOCKSTEP
#define WB_SHADOW_LOCKSTEP 1
#endif
// Geometries, materials, textures, the environment map; vertex fetch, material inputs (shared with the hybrid
// modes).
#include "../shared/scene.glsl"

layout(set = 0, binding = WB_BIND_TLAS) uniform accelerationStructureEXT tlas;
layout(set = 0, binding = WB_BIND_FRAME, scalar) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = WB_BIND_LIGHTS, scalar) readonly buffer LightBlock { DirectionalLight lights[]; };
layout(set = 0, binding = WB_BIND_ENV_ALIAS, scalar) readonly buffer EnvAliasBlock { EnvAliasEntry entries[]; } envAliasBuffer;
layout(set = 0, binding = WB_BIND_COUNTERS, scalar) buffer CounterBlock { Counters counters; };
layout(set = 0, binding = WB_BIND_BLUE_NOISE, scalar) readonly buffer BlueNoiseBlock { uint texels[]; } blueNoiseBuffer;
layout(set = 0, binding = WB_BIND_SOBOL, scalar) readonly buffer SobolBlock { uint dirs[]; } sobolBuffer;

layout(push_constant, scalar) uniform PushBlock { PushConstants pc; };

// Table accessors the shared sampling headers use (shared/random.h, shared/env_sampling.h).
#define WB_ENV_ALIAS(i) envAliasBuffer.entries[(i)]
#define WB_SOBOL_DIR(dim, bit) sobolBuffer.dirs[(dim) * 32u + (bit)]
#define WB_BLUE_NOISE(x, y) wbUnpackBlueNoise(blueNoiseBuffer.texels[(y) * 128u + (x)])

// The sample this invocation traces: a launch of depth N traces samples pc.sampleIndex .. + N - 1 (raygen writes
// them to the sample slots; resolve.comp accumulates them in order).
#define WB_SAMPLE_INDEX (pc.sampleIndex + gl_LaunchIDEXT.z)

// The pixel this invocation traces. With lane isolation (WB_COST_ISOLATE, raygen.rgen) one lane of each subgroup
// traces pixels it takes from a queue, so the pixel is not the launch ID: raygen puts the pixel's index within
// the launch in the payload, where every stage reads it.
#if WB_COST_ISOLATE
#define WB_PIXEL                                                                                                \
  (pc.tileOffset + uvec2(payload.launchPixel % gl_LaunchSizeEXT.x, payload.launchPixel / gl_LaunchSizeEXT.x))
#else
#define WB_PIXEL (gl_LaunchIDEXT.xy + pc.tileOffset)
#endif

#define PATH_PAYLOAD_LOCATION 0
#define MISS_ENV 0u
#define MISS_SHADOW 1u

// The split path loop (PathTracer::splitsShadows; on GPUs by default, WB_SPLIT_SHADOWS=0|1 in the environment):
// raygen traces the path rays and leaves each vertex's shadow requests in a buffer (PushConstants::splitSlots
// per sample; the rest it traces itself); a second launch of its own small pipeline (shadow_split.rgen) traces
// them and accumulates the sample. A wavefront split of the path loop in two stages: the shadow rays run in a
// kernel with few registers and all lanes on the same kind of ray (docs/bench/roofline.md).
#ifndef WB_SPLIT_SHADOWS
#define WB_SPLIT_SHADOWS 0
#endif
#if WB_SPLIT_SHADOWS
layout(set = 0, binding = WB_BIND_SPLIT_REQUESTS, scalar) buffer SplitRequestBlock { vec4 splitRequests[]; };
layout(set = 0, binding = WB_BIND_SPLIT_PATHS, scalar) buffer SplitPathBlock { vec4 splitPaths[]; };
// The sample's record: one per pixel and sample of the launch (as the sample slots).
uint splitIndex(uvec2 pixel) { return (gl_LaunchIDEXT.z * pc.imageSize.y + pixel.y) * pc.imageSize.x + pixel.x; }
#endif

// WB_INSPECT=1: the path inspector's build, which records every vertex of the inspected pixel's paths
// (inspect.glsl). The host compiles it only while a pixel is inspected.
#ifndef WB_INSPECT
#define WB_INSPECT 0
#endif
#if WB_INSPECT
#include "inspect.glsl"
#endif

// WB_COST=1: the cost variant, which measures every sample with the shader clock into the cost AOV
// (WB_BIND_AOV_COST). It and the inspecting variant time the trace calls and the shading (WB_TIMED): the hit and
// miss shaders hand their own time back in the payload.
#ifndef WB_COST
#define WB_COST 0
#endif
#if (WB_COST != 0 || WB_INSPECT != 0) && WB_CLOCK != 0
#define WB_TIMED 1
#else
#define WB_TIMED 0
#endif
#if WB_COST || WB_INSPECT
// The low 32 bits of the clock: a sample's or a call's span fits them, and unsigned subtraction survives a wrap.
#if WB_CLOCK == 1
uint wbClock() { return clock2x32ARB().x; }
#elif WB_CLOCK == 2
uint wbClock() { return clockRealtime2x32EXT().x; }
#else
uint wbClock() { return 0u; }
#endif
#endif

// wbPrint / wbAssert (shared/debug_print.h), recorded in the inspecting and asserts variants (debug.glsl).
#include "debug.glsl"

#endif
