// The scene as every renderer's shaders see it, defined once for C++ and GLSL: vertices, geometry records,
// materials, directional lights (the sun model), emissive triangles, alias table entries, environment kinds.
// Layouts are std430/scalar-compatible: vec3 members are always followed by a 4-byte scalar.
#ifndef WB_SCENE_TYPES_H
#define WB_SCENE_TYPES_H
#include "glsl_cpp.h"

// Material alpha modes (glTF).
#define WB_ALPHA_OPAQUE 0u
#define WB_ALPHA_MASK 1u
#define WB_ALPHA_BLEND 2u

// Material flags.
#define WB_MATERIAL_DOUBLE_SIDED 1u

// What lights the scene from afar (scene::EnvironmentKind takes its values from these; WB_ENV_MODE of the
// path tracer's specialised build is one of them).
#define WB_ENV_NONE 0     // black
#define WB_ENV_CONSTANT 1 // a constant colour
#define WB_ENV_MAP 2      // an equirectangular map (the generic path tracer build reads a constant as a 1x1 map)

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

// A directional light (KHR_lights_punctual), the sun: a disc of angular radius acos(cosAngularRadius) around
// -direction, or a delta light when cosAngularRadius is 1 (glTF lights are; `--sun-angle` gives them a size).
// `radiance` is what a surface facing the light receives, whatever its size: the irradiance at normal incidence
// (glTF's illuminance in lux, times the colour). The disc's own radiance is that irradiance over the disc's
// projected solid angle, radiance / (pi sin^2(angular radius)) (shared/sun.h), so a sun keeps its power at normal
// incidence, and a fully visible sun lights a diffuse surface the same, whatever its size.
struct DirectionalLight {
  vec3 direction;  // unit vector the light travels along (from the light into the scene)
  float cosAngularRadius;  // cosine of the disc's angular radius (half its angular diameter); 1: a delta light
  vec3 radiance;  // colour * intensity: the irradiance on a surface facing the light (not the disc's radiance)
  float pad0;
};

// Alias table entry for importance sampling (one per environment map pixel, or per emissive triangle).
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

WB_NAMESPACE_END

#endif
