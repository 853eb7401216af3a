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
// rgba32f storage image, the heat maps' data (AOV): r = mean luminance^2 of the accumulated samples (with the
// accumulation's mean: per-pixel variance), g = fraction of paths Russian roulette ended, b = mean over all paths
// of the bounce where it ended them (0 for the others: b / g is the mean over those it ended), a = the lowest
// bounce at which a sample became NaN/Inf (WB_NO_NON_FINITE: none)
#define WB_BIND_AOV_STATS 20
#define WB_NO_NON_FINITE 1.0e30
// The path inspector's buffers, declared only by the WB_INSPECT build of the path tracer (shaders/pathtracer/inspect.glsl).
#define WB_BIND_INSPECT_HEADER 17    // storage buffer InspectHeader: which pixel and how many records
#define WB_BIND_INSPECT_SAMPLES 18   // storage buffer InspectSample[]: one per recorded sample
#define WB_BIND_INSPECT_VERTICES 19  // storage buffer InspectVertex[]: vertexCapacity per recorded sample

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

// ==== Path inspector (WB_INSPECT builds of the path tracer; src/render/path_inspector.h reads the records) ====
#define WB_INSPECT_MAX_LIGHT_SAMPLES 4u  // light samples recorded per vertex (more are counted, not recorded)
#define WB_INSPECT_NO_SAMPLE 0xffffffffu  // InspectSample.sampleIndex of a slot not written yet

// InspectHeader.mode: which samples are recorded.
#define WB_INSPECT_FIRST 0u  // samples firstSample .. firstSample + sampleCapacity - 1, in slot sampleIndex - firstSample
#define WB_INSPECT_RING 1u   // every sample, in slot sampleIndex % sampleCapacity (the latest ones stay)

// InspectVertex.flags
#define WB_INSPECT_FRONT_FACE 1u      // the ray hit the side the triangle's winding faces
#define WB_INSPECT_NORMAL_FLIPPED 2u  // the interpolated normal pointed away from the ray's side and was flipped
#define WB_INSPECT_CONTINUED 4u       // a valid continuation direction was sampled

// InspectVertex.rrOutcome
#define WB_INSPECT_RR_NOT_APPLIED 0u  // before rr_start, Russian roulette off, or the path ended before it
#define WB_INSPECT_RR_SURVIVED 1u
#define WB_INSPECT_RR_TERMINATED 2u

// InspectLightSample.kind
#define WB_INSPECT_LIGHT_DIRECTIONAL 0u  // index: the directional light
#define WB_INSPECT_LIGHT_ENVIRONMENT 1u  // index: -1
#define WB_INSPECT_LIGHT_EMITTER 2u      // index: the emissive triangle (WB_BIND_EMITTERS)

// InspectLightSample.status
#define WB_INSPECT_NEE_TRACED 0u        // a shadow ray was traced (visible: its outcome)
#define WB_INSPECT_NEE_NO_SAMPLE 1u     // the strategy gave no sample (pdf 0, back of a single-sided emitter)
#define WB_INSPECT_NEE_BELOW_SURFACE 2u // the light is below the geometric surface
#define WB_INSPECT_NEE_ZERO_BRDF 3u     // the BRDF is zero towards the light

// InspectSample.end: why the path ended.
#define WB_INSPECT_END_ESCAPED 0u       // the last ray left the scene (the environment)
#define WB_INSPECT_END_ABSORBED 1u      // no valid continuation (a sample below the surface, pdf 0)
#define WB_INSPECT_END_MAX_BOUNCES 2u
#define WB_INSPECT_END_RUSSIAN_ROULETTE 3u
#define WB_INSPECT_END_ZERO_THROUGHPUT 4u  // the throughput became zero, NaN or infinite

// Non-finite terms (InspectVertex.nonFinite and InspectSample.nonFinite bits): the first term, in the order a
// vertex computes them, of the first vertex that has one is where a NaN/Inf came from.
#define WB_INSPECT_NAN_SHADING_NORMAL 1u
#define WB_INSPECT_NAN_EMISSION 2u
#define WB_INSPECT_NAN_LIGHT 4u       // a light sample's radiance, pdf, MIS weight or contribution
#define WB_INSPECT_NAN_BRDF 8u        // f * cos of the sampled direction
#define WB_INSPECT_NAN_PDF 16u
#define WB_INSPECT_NAN_WEIGHT 32u     // f * cos / pdf
#define WB_INSPECT_NAN_THROUGHPUT 64u // the throughput after the vertex (Russian roulette included)
#define WB_INSPECT_NAN_ENVIRONMENT 128u  // the escaped ray's (MIS-weighted) environment radiance
#define WB_INSPECT_NAN_RADIANCE 256u  // the sample's sum (finite terms that overflowed)
// raygen: what the vertex added to the sample (closest-hit's payload radiance, a visible light sample's) while
// every term closest-hit recorded is finite. In the order of computation it comes after WB_INSPECT_NAN_WEIGHT
// and before WB_INSPECT_NAN_THROUGHPUT (render/path_inspector.cpp lists the order).
#define WB_INSPECT_NAN_ADDED 512u

// Which pixel is inspected and how many records fit; written by the host.
struct InspectHeader {
  uvec2 pixel;
  uint mode;            // WB_INSPECT_FIRST | WB_INSPECT_RING
  uint firstSample;     // WB_INSPECT_FIRST: the first sample recorded
  uint sampleCapacity;  // InspectSample records
  uint vertexCapacity;  // InspectVertex records per sample (vertices beyond are traced, not recorded)
  uint pad0;
  uint pad1;
};

// One light sample of next-event estimation at a vertex. Written by closest-hit, except `visible` (raygen,
// after the shadow ray).
struct InspectLightSample {
  vec3 direction;     // towards the light (the BRDF's wi)
  uint kind;          // WB_INSPECT_LIGHT_*
  vec3 radiance;      // Le arriving along direction
  int index;          // directional light or emitter triangle; -1 for the environment
  vec3 brdfCos;       // f * cos towards the light
  float lightPdf;     // solid-angle pdf of the light strategy (0: a delta light)
  vec3 contribution;  // f * Le * MIS weight / lightPdf (delta: f * Le): added times the throughput when visible
  float brdfPdf;      // pdf with which BRDF sampling picks direction (MIS's other strategy)
  float misWeight;    // power heuristic weight (1 for delta lights and without MIS)
  float distance;     // the shadow ray's length (1e30: unbounded)
  uint status;        // WB_INSPECT_NEE_*
  uint visible;       // raygen: 1 when the shadow ray reached the light
};

// One surface vertex of a recorded path. Written by closest-hit, except the fields marked raygen.
struct InspectVertex {
  vec3 position;         // world space
  float distance;        // along the incoming ray
  vec3 geometricNormal;  // facing the incoming ray
  uint flags;            // WB_INSPECT_FRONT_FACE | ...
  vec3 shadingNormal;    // as shaded: interpolated, normal-mapped, flipped and bent towards the viewer
  int instance;          // gl_InstanceID
  vec3 incoming;         // direction of the ray that hit the vertex
  int primitive;         // gl_PrimitiveID (triangle of the geometry)
  vec3 emitted;          // emitted radiance times its MIS weight (not yet times the throughput)
  int material;
  vec3 direction;        // the sampled continuation direction
  uint lobe;             // WB_LOBE_DIFFUSE | WB_LOBE_SPECULAR
  vec3 brdf;             // f (no cosine) for direction
  float lobeProbability; // probability of choosing that lobe
  vec3 weight;           // f * cos / pdf: the throughput's factor
  float pdf;             // combined solid-angle pdf of direction (0: no valid continuation)
  vec3 throughputIn;     // raygen: the path throughput arriving at the vertex
  float cosine;          // shading normal . direction
  vec3 throughput;       // raygen: after the vertex: throughputIn * weight / rrProbability
  float rrProbability;   // raygen: Russian roulette survival probability (1 when it did not run)
  float emissionMis;     // MIS weight of the emission (1 unless a BRDF-sampled ray hit an emitter NEE samples)
  int geometry;          // GeometryInfo index (instance custom index + geometry index)
  uint rrOutcome;        // raygen: WB_INSPECT_RR_*
  uint nonFinite;        // WB_INSPECT_NAN_* bits closest-hit saw
  uint pathNonFinite;    // raygen: WB_INSPECT_NAN_* bits (added, throughput)
  uint lightSamples;     // light samples taken (records: at most WB_INSPECT_MAX_LIGHT_SAMPLES)
  vec3 added;            // raygen: what it added to the sample at this vertex: throughputIn * (the payload's
                         // radiance + the radiance of every shadow request that reached its light)
  uint pad0;
  InspectLightSample lights[WB_INSPECT_MAX_LIGHT_SAMPLES];
};

// One recorded sample of the inspected pixel. Written by raygen, except the escape's environment and MIS weight
// (the miss shader).
struct InspectSample {
  uint sampleIndex;  // the accumulation's sample index; WB_INSPECT_NO_SAMPLE: slot not written
  uint vertexCount;  // surface vertices of the path (records: at most vertexCapacity)
  uint end;          // WB_INSPECT_END_*
  uint accumulated;  // 1 when the sample was finite and went into the pixel's average
  vec3 radiance;     // the sample's value: what raygen accumulated (or dropped)
  uint shadowRays;
  vec3 cameraOrigin;
  uint escaped;      // 1 when the last ray escaped: the escape fields hold
  vec3 cameraDirection;
  uint nonFinite;    // WB_INSPECT_NAN_ENVIRONMENT | WB_INSPECT_NAN_RADIANCE
  vec3 escapeDirection;
  float escapeMis;   // miss shader: the environment's MIS weight
  vec3 escapeEnvironment;  // miss shader: environment radiance along escapeDirection (no weight)
  float pad0;
  vec3 escapeThroughput;   // the throughput of the escaping ray
  float pad1;
  vec3 escapeRadiance;     // escapeEnvironment * escapeMis: added times escapeThroughput
  float pad2;
  vec2 jitter;       // the sample's position in the pixel
  float pad3;
  float pad4;
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
#define WB_BIND_HYBRID_INSPECT 50    // storage buffer HybridInspectRecord: the rays of the inspected pixel

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
  uint inspectX;  // the pixel whose rays are recorded in WB_BIND_HYBRID_INSPECT (WB_HYBRID_NO_INSPECT: none)
  uint inspectY;
};

#define WB_HYBRID_NO_INSPECT 0xffffffffu
#define WB_HYBRID_INSPECT_MAX_AO 64u          // AO rays recorded (ao_rays is at most 64)
#define WB_HYBRID_INSPECT_MAX_REFLECTIONS 16u  // reflection bounces recorded (reflection_depth is at most 16)

// A shadow or AO ray of the inspected pixel.
struct HybridInspectRay {
  vec3 direction;
  uint traced;   // 0: not traced (a sun below the surface)
  vec3 origin;
  uint visible;  // 1: nothing hit within its length (lit / open)
};

// One bounce of the inspected pixel's reflection.
struct HybridInspectBounce {
  vec3 direction;      // of the ray traced
  uint hit;            // 0: it escaped to the environment
  vec3 position;       // the hit
  float roughness;
  vec3 normal;         // shading normal at the hit
  float metallic;
  vec3 throughput;     // of the ray traced
  float sunVisible;    // the hit's shadow ray (0 also when the sun is below it)
  vec3 added;          // radiance this bounce added to the reflection (throughput included)
  float pad0;
};

// The rays of the inspected pixel in the last frame: written by the shadow/AO raygen (G-buffer point, shadow and
// AO rays, this frame's values and the temporal averages) and the reflection raygen.
struct HybridInspectRecord {
  uint frameIndex;   // the frame that wrote it (WB_HYBRID_NO_INSPECT: none yet)
  uint covered;      // 1: the G-buffer has a surface at the pixel
  uint aoRays;
  uint reflectionBounces;  // recorded bounces (0: no reflection traced)
  vec3 position;
  float shadow;      // this frame's sun visibility
  vec3 normal;
  float ao;          // this frame's open fraction
  float shadowAverage;  // what the shadow mask holds (temporal average)
  float aoAverage;
  uint reflected;    // 1: the reflection pass traced this pixel
  float pad0;
  vec3 reflection;   // the reflected radiance the pass wrote
  float pad1;
  HybridInspectRay shadowRay;
  HybridInspectRay aoRay[WB_HYBRID_INSPECT_MAX_AO];
  HybridInspectBounce bounces[WB_HYBRID_INSPECT_MAX_REFLECTIONS];
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
