// Every struct and binding number that crosses the host/shader boundary, defined once for C++ and GLSL.
// Layouts are std430/scalar-compatible: vec3 members are always followed by a 4-byte scalar.
#ifndef WB_GPU_TYPES_H
#define WB_GPU_TYPES_H
#include "glsl_cpp.h"

// ---- descriptor set 0 bindings of the ray tracing pipelines ----
#define WB_BIND_TLAS 0          // accelerationStructureEXT
#define WB_BIND_ACCUM 1         // rgba32f storage image: running average of radiance
#define WB_BIND_FRAME 2         // uniform buffer FrameUniforms
#define WB_BIND_GEOMETRIES 3    // storage buffer GeometryInfo[] (indexed by instance custom index + geometry index)
#define WB_BIND_MATERIALS 4     // storage buffer Material[]
#define WB_BIND_LIGHTS 5        // storage buffer DirectionalLight[]
#define WB_BIND_TEXTURES 6      // sampler2D[] (runtime array, descriptor indexing)
#define WB_BIND_ENV_MAP 7       // sampler2D: equirectangular environment (1x1 when constant colour)
#define WB_BIND_ENV_ALIAS 8     // storage buffer EnvAliasEntry[] (importance sampling table)
#define WB_BIND_AOV_ALBEDO 9    // rgba16f storage image: first-hit base colour, a = fraction of samples dropped (NaN/Inf)
#define WB_BIND_AOV_NORMAL 10   // rgba16f storage image: first-hit shading normal, a = first-hit distance (-1 = miss)
#define WB_BIND_COUNTERS 11     // storage buffer Counters
#define WB_BIND_BLUE_NOISE 12   // storage buffer uint[] 128x128 blue-noise (rg in 16 bits each)
#define WB_BIND_SOBOL 13        // storage buffer uint[] Sobol direction numbers [dim * 32 + bit]
#define WB_BIND_AOV_INFO 14     // rgba16f storage image: first-hit geometric normal, a = path vertices traced
#define WB_BIND_EMITTERS 15     // storage buffer EmissiveTriangle[] (world space), for next-event estimation
#define WB_BIND_EMITTER_ALIAS 16  // storage buffer EnvAliasEntry[] over emitters, weights = luminance * area

// Material alpha modes (glTF).
#define WB_ALPHA_OPAQUE 0u
#define WB_ALPHA_MASK 1u
#define WB_ALPHA_BLEND 2u

// Material flags.
#define WB_MATERIAL_DOUBLE_SIDED 1u

// Push-constant flags.
#define WB_FLAG_SAMPLER_PCG 1u       // PCG random numbers instead of Sobol + blue noise
#define WB_FLAG_NO_NEE 2u            // disable next-event estimation (BRDF sampling only)
#define WB_FLAG_NO_BRDF_MIS 4u       // light sampling only for the environment (no MIS with BRDF)
#define WB_FLAG_NO_RR 8u             // Russian roulette off
#define WB_FLAG_AOV 16u              // write the AOV images (albedo, normals, depth, bounces, dropped samples)
#define WB_FLAG_SAMPLER_OWEN 32u     // Owen-scrambled Sobol (shared/random.h) instead of Sobol + blue noise

WB_NAMESPACE_BEGIN

// Interleaved vertex as stored in device memory, fetched through buffer device addresses.
struct Vertex {
  vec3 position;
  float u;
  vec3 normal;
  float v;
  vec4 tangent;  // xyz tangent, w handedness; all zero when the mesh has none and none could be generated
};

// One entry per BLAS geometry (mesh primitive): where its data lives and what it is made of.
struct GeometryInfo {
  uint vertexAddressLo;  // buffer device address split in two 32-bit halves (no int64 needed in GLSL)
  uint vertexAddressHi;
  uint indexAddressLo;
  uint indexAddressHi;
  uint materialIndex;
  uint vertexCount;
  uint triangleCount;
  uint pad0;
};

// glTF 2.0 metallic-roughness material, extensions folded in. Texture indices are -1 when absent.
struct Material {
  vec4 baseColorFactor;
  vec3 emissive;  // emissiveFactor * KHR_materials_emissive_strength
  float metallic;
  vec3 specularColorFactor;  // KHR_materials_specular
  float roughness;
  float specularFactor;  // KHR_materials_specular (1 when absent)
  float alphaCutoff;
  uint alphaMode;
  uint flags;
  int baseColorTexture;
  int normalTexture;
  int metallicRoughnessTexture;
  int emissiveTexture;
  float normalScale;
  float pad0;
  float pad1;
  float pad2;
};

// KHR_lights_punctual directional light.
struct DirectionalLight {
  vec3 direction;  // unit vector the light travels along (from the light into the scene)
  float cosAngularRadius;  // 1 for a delta light
  vec3 radiance;  // colour * intensity (irradiance on a surface facing the light, W/m^2 style units)
  float pad0;
};

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
  float pad0;
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
};

// Alias table entry for environment importance sampling (one per env-map pixel).
struct EnvAliasEntry {
  float prob;  // probability of keeping this entry (vs. its alias)
  uint alias;
  float pdf;  // pdf of choosing this pixel (its weight / total weight)
  float pad0;
};

// An emissive triangle in world space, for next-event estimation of area lights. Its selection probability is
// luminance(material emissive factor) * area / FrameUniforms::emitterTotalPower, so the area-measure pdf of a point
// on it is luminance(emissive factor) / emitterTotalPower, computable at any hit without a lookup.
struct EmissiveTriangle {
  vec3 p0;
  uint materialIndex;
  vec3 p1;
  uint doubleSided;
  vec3 p2;
  float area;
  vec2 uv0;
  vec2 uv1;
  vec2 uv2;
  vec2 pad0;
};

// Counters the host reads back.
struct Counters {
  uint droppedSamples;  // NaN/Inf samples not accumulated
  uint rayCount;        // all rays traced (approximate, atomics per pixel)
  uint shadowRayCount;
  uint pathCount;
};

WB_NAMESPACE_END

// ==== Hybrid raster + ray traced modes (src/render/hybrid, shaders/hybrid) ====
// Descriptor set 0 bindings of the hybrid programs (G-buffer raster, shadow/AO and reflection ray tracing,
// composite compute). They also use WB_BIND_TLAS, WB_BIND_GEOMETRIES, WB_BIND_MATERIALS, WB_BIND_TEXTURES and
// WB_BIND_ENV_MAP above with the same meaning.
#define WB_BIND_HYBRID_FRAME 40      // uniform buffer HybridUniforms
#define WB_BIND_GBUF_ALBEDO 41       // sampler2D rgba8: rgb base colour (linear), a metallic
#define WB_BIND_GBUF_NORMAL 42       // sampler2D rgba16f: xyz world shading normal facing the camera, w roughness
#define WB_BIND_GBUF_DEPTH 43        // sampler2D D32: reversed-Z depth (0 = background)
#define WB_BIND_GBUF_EMISSIVE 44     // sampler2D rgba16f: rgb emitted radiance, a unused
#define WB_BIND_SHADOW_MASK 45       // r8 storage image: sun visibility (temporally averaged when enabled)
#define WB_BIND_AO_MASK 46           // r8 storage image: ambient occlusion (1 = open)
#define WB_BIND_HYBRID_HISTORY 47    // rgba16f storage image: r shadow, g AO running averages
#define WB_BIND_REFLECTION 48        // rgba16f storage image: rgb reflected radiance, a 1 where traced
#define WB_BIND_HYBRID_OUTPUT 49     // rgba32f storage image: composited linear radiance

#define WB_HYBRID_FLAG_REFLECTIONS 1u  // the reflection pass ran: composite uses WB_BIND_REFLECTION
#define WB_HYBRID_FLAG_AO 2u           // ambient occlusion rays are traced
#define WB_HYBRID_FLAG_TEMPORAL 4u     // accumulate shadow/AO over frames while frameIndex > 0

WB_NAMESPACE_BEGIN

// Per-frame uniforms of the hybrid modes (binding WB_BIND_HYBRID_FRAME).
struct HybridUniforms {
  mat4 viewProj;         // world -> clip; Vulkan y down, reversed-Z infinite projection (depth = near / distance)
  mat4 viewProjInverse;  // clip -> world
  vec3 cameraPosition;
  uint frameIndex;  // frames averaged so far while the camera is still (0 = first: overwrite history)
  vec3 sunDirection;  // unit vector the sunlight travels along
  float sunCosAngle;  // cosine of the sun's angular radius (1 = hard shadows)
  vec3 sunRadiance;   // irradiance of a surface facing the sun
  uint hasSun;
  vec3 ambient;  // constant environment radiance (times intensity) when envMapPresent == 0
  float aoRadius;
  uint aoRays;
  uint flags;  // WB_HYBRID_FLAG_*
  uint width;
  uint height;
  float reflectionMaxRoughness;  // reflections are traced for roughness below this
  float envIntensity;
  float envRotation;  // radians about +Y
  uint envMapPresent;
  uint seed;
  float reflectionMinMetallic;   // ... and metallic at least this (0 = smooth dielectrics too)
  float pad1;
  float pad2;
};

// Push constants of the G-buffer draw: one draw per (instance, primitive).
struct HybridDrawConstants {
  mat4 model;  // object -> world
  uint geometryIndex;  // GeometryInfo entry of the primitive
  uint pad0;
  uint pad1;
  uint pad2;
};

WB_NAMESPACE_END

#endif
