// The path inspector's records (WB_INSPECT builds of the path tracer; src/render/path_inspector.h reads them),
// defined once for C++ and GLSL. Layouts are std430/scalar-compatible.
#ifndef WB_INSPECT_TYPES_H
#define WB_INSPECT_TYPES_H
#include "glsl_cpp.h"

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

WB_NAMESPACE_BEGIN

// Which pixel is inspected and how many records fit; written by the host.
struct InspectHeader {
  uvec2 pixel;
  uint mode;            // WB_INSPECT_FIRST | WB_INSPECT_RING
  uint firstSample;     // WB_INSPECT_FIRST: the first sample recorded
  uint sampleCapacity;  // InspectSample records
  uint vertexCapacity;  // InspectVertex records per sample (vertices beyond are traced, not recorded)
  uint clock;           // which shader clock the cost fields count (WB_CLOCK_*); written by the host
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
  // raygen, in the shader clock's units (0 where the device has none: InspectHeader.clock): the cost of the
  // vertex. shadeClocks: closest-hit's shading here; traceClocks: the trace call that found the vertex less
  // that shading (traversal, any-hit); shadowClocks: the trace calls of its shadow rays.
  uint shadeClocks;
  uint traceClocks;
  uint shadowClocks;
  uint pad0;
  uint pad1;
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
  uint prints;             // wbPrint calls the sample made (records: at most WB_PRINTS_PER_SAMPLE)
  vec3 escapeRadiance;     // escapeEnvironment * escapeMis + escapeSun: added times escapeThroughput
  float pad2;
  vec2 jitter;       // the sample's position in the pixel
  uint clocks;       // raygen: the whole sample, in the shader clock's units (0 without one)
  uint escapeClocks; // raygen: the trace call of the escaping ray, its miss shader included
  vec3 escapeSun;    // miss shader: the discs of suns of angular size along escapeDirection, MIS-weighted
  float pad5;
};

WB_NAMESPACE_END

#endif
