// Resources and helpers shared by every stage of the path tracer (bindings come from shared/bindings.h).
#ifndef WB_PT_COMMON_GLSL
#define WB_PT_COMMON_GLSL

#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require

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

#define PATH_PAYLOAD_LOCATION 0
#define MISS_ENV 0u
#define MISS_SHADOW 1u

// WB_INSPECT=1: the path inspector's build, which records every vertex of the inspected pixel's paths
// (inspect.glsl). The host compiles it only while a pixel is inspected.
#ifndef WB_INSPECT
#define WB_INSPECT 0
#endif
#if WB_INSPECT
#include "inspect.glsl"
#endif

#endif
