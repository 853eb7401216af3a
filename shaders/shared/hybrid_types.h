// The hybrid modes' uniforms, inspector record and draw constants (src/render/hybrid, shaders/hybrid), defined
// once for C++ and GLSL. Layouts are std430/scalar-compatible: vec3 members are always followed by a 4-byte scalar.
#ifndef WB_HYBRID_TYPES_H
#define WB_HYBRID_TYPES_H
#include "glsl_cpp.h"

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
  float sunCosAngle;  // cosine of the sun's angular radius (1: a delta light, hard shadows)
  vec3 sunRadiance;   // irradiance of a surface facing the sun (DirectionalLight.radiance)
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
#define WB_HYBRID_INSPECT_MAX_AO 64u          // AO rays recorded: the most ao_rays takes (render/parameters.cpp)
#define WB_HYBRID_INSPECT_MAX_REFLECTIONS 16u  // bounces recorded: the most reflection_depth takes

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
