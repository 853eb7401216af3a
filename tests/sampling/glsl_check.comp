#version 460
// Compile check of the shared sampling headers as GLSL: run by ctest (glsl_sampling_*) with -DWB_CHECK_<header>.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_scalar_block_layout : require
layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/gpu_types.h"
layout(std430, set = 0, binding = WB_BIND_ENV_ALIAS) readonly buffer EnvAliasBuf { EnvAliasEntry entries[]; } envAliasBuffer;
layout(std430, set = 0, binding = WB_BIND_SOBOL) readonly buffer SobolBuf { uint dirs[]; } sobolBuffer;
layout(std430, set = 0, binding = WB_BIND_BLUE_NOISE) readonly buffer BlueNoiseBuf { uint texels[]; } blueNoiseBuffer;
layout(std430, set = 0, binding = 31) buffer OutBuf { vec4 v[]; } outBuf;
#define WB_ENV_ALIAS(i) envAliasBuffer.entries[(i)]
#define WB_SOBOL_DIR(dim, bit) sobolBuffer.dirs[(dim) * 32u + (bit)]
#define WB_BLUE_NOISE(x, y) wbUnpackBlueNoise(blueNoiseBuffer.texels[(y) * 128u + (x)])

#if defined(WB_CHECK_sampling_math)
#include "shared/sampling_math.h"
void main() {
  vec3 d = sampleCosineHemisphere(vec2(0.3, 0.4));
  vec3 h = sampleGgxVndf(d, ggxAlpha(0.5), vec2(0.1, 0.2));
  vec3 t, b;
  buildOrthonormalBasis(d, t, b);
  vec2 uv = directionToEquirect(h, 0.3);
  outBuf.v[0] = vec4(offsetRay(d, h) + toWorld(t, t, b, d) + equirectToDirection(uv, 0.1),
                     ggxVndfPdf(d, h, 0.1) + ggxReflectionPdf(d, h, 0.1) + powerHeuristic(1.0, 2.0, 1.0, 3.0));
}
#elif defined(WB_CHECK_brdf)
#include "shared/brdf.h"
void main() {
  SurfaceMaterial m = makeSurfaceMaterial(vec3(0.8), 0.5, 0.3);
  vec3 n = normalize(vec3(0.1, 0.2, 1.0));
  vec3 wo = normalize(vec3(0.3, 0.1, 1.0));
  BrdfSample s = brdfSample(m, n, wo, vec3(0.1, 0.2, 0.3));
  outBuf.v[0] = vec4(brdfEval(m, n, wo, s.wi) + s.weight, brdfPdf(m, n, wo, s.wi) + float(s.lobe));
}
#elif defined(WB_CHECK_random)
#include "shared/random.h"
void main() {
  SamplerState s = samplerInit(gl_GlobalInvocationID.xy, 3u, 7u, WB_SAMPLER_OWEN);
  uint st = 5u;
  outBuf.v[0] = vec4(samplerGet3D(s, sampleDimension(1u, WB_DIM_LOBE)),
                     samplerGet2D(s, WB_DIM_PIXEL).x + float(owenBits(2u, 3u, 4u, 1u)) + float(nestedUniformScramble(5u, 6u)) + pcgNextFloat(st) + hashStreamNext(st));
}
#elif defined(WB_CHECK_env_sampling)
#include "shared/env_sampling.h"
void main() {
  EnvSample e = envSample(vec3(0.1, 0.2, 0.3), 1024u, 512u, 0.5);
  outBuf.v[0] = vec4(e.dir, e.pdf + envPdf(e.dir, 1024u, 512u, 0.5));
}
#elif defined(WB_CHECK_spherical_triangle)
#include "shared/spherical_triangle.h"
void main() {
  vec3 p = vec3(0.1, 0.2, 0.3), p0 = vec3(1, 0, 0), p1 = vec3(0, 1, 0), p2 = vec3(0, 0, 1);
  float omega = sphericalTriangleSolidAngle(p, p0, p1, p2);
  vec3 d = sampleSphericalTriangle(p, p0, p1, p2, vec2(0.3, 0.6), omega);
  outBuf.v[0] = vec4(d + sphericalTriangleHit(p, d, p0, p1, p2), sphericalTriangleUseSolidAngle(p, p0, p1, p2) ? 1.0 : 0.0);
  TriangleLightSample s = triangleLightSample(p, p0, p1, p2, vec2(0.3, 0.6), 1.0);
  outBuf.v[1] = vec4(s.wi + sphericalTriangleSample(sphericalTriangleSetup(p, p0, p1, p2), vec2(0.2, 0.7)),
                     s.pdf + triangleLightPdf(p, p0, p1, p2, s.dist, s.cosLight, 1.0));
}
#elif defined(WB_CHECK_sun)
#include "shared/sun.h"
void main() {
  vec3 d = sampleCone(normalize(vec3(0.1, -1.0, 0.2)), 0.99, vec2(0.3, 0.6));
  outBuf.v[0] = vec4(sunRadianceAlong(d, vec3(0.0, -1.0, 0.0), 0.99, sunDiscRadiance(vec3(2.0), 0.99)),
                     sunConePdf(0.99) + (sunIsDelta(1.0) ? 1.0 : 0.0));
}
#else
#include "shared/brdf.h"
#include "shared/random.h"
#include "shared/env_sampling.h"
#include "shared/sun.h"
#include "shared/sampling_math.h"
void main() {
  SamplerState s = samplerInit(gl_GlobalInvocationID.xy, 3u, 7u, WB_SAMPLER_OWEN);
  SurfaceMaterial m = makeSurfaceMaterial(vec3(0.8), 1.0, 0.0);
  BrdfSample bs = brdfSample(m, vec3(0, 0, 1), vec3(0, 0.6, 0.8), samplerGet3D(s, sampleDimension(0u, WB_DIM_LOBE)));
  EnvSample es = envSample(samplerGet3D(s, sampleDimension(0u, WB_DIM_LIGHT)), 64u, 32u, 0.0);
  outBuf.v[0] = vec4(bs.weight + es.dir, powerHeuristic(1.0, bs.pdf, 1.0, es.pdf));
}
#endif
