// Continuation directions: the BRDF's, mixed at surfaces with a diffuse lobe with directions towards the scene's
// glossy reflectors (src/scene/reflectors.h). A light reflected by a smooth object onto a diffuse surface (the sun
// focused by a metal sphere onto the ground: a caustic) is a small, bright target that cosine sampling meets
// rarely: the rare paths that do are fireflies. With probability c = WB_REFLECTOR_FRACTION x (the diffuse lobe's
// probability) the direction is uniform in the cone of one reflector's bounding sphere (picked uniformly among
// those the point sees above its surface), otherwise the BRDF's; the pdf is the mixture's, defensive through the
// BRDF's part, so every estimate that weighs against BRDF sampling (next-event estimation's MIS, the miss and
// emission weights through payload.pdf) uses pathPdf. Without reflectors (c = 0) it is plain BRDF sampling.
// On by default (docs/bench/roofline.md: on the sunlit glossy scene and the default scene less error for the
// time on lavapipe and an H100, most where caustic fireflies rule the error); --define WB_REFLECTOR_GUIDING=0
// turns it off, WB_REFLECTOR_FRACTION=F sets the fraction.
#ifndef WB_PT_GUIDING_GLSL
#define WB_PT_GUIDING_GLSL
#include "../shared/brdf.h"
#include "../shared/sun.h"

#ifndef WB_REFLECTOR_GUIDING
#if defined(WB_SPECIALIZED) && !WB_HAS_REFLECTORS
#define WB_REFLECTOR_GUIDING 0  // a scene without glossy reflectors: plain BRDF sampling, none of the code
#else
#define WB_REFLECTOR_GUIDING 1
#endif
#endif
#ifndef WB_REFLECTOR_FRACTION
#define WB_REFLECTOR_FRACTION 0.3
#endif
// Coherent choices: the number that picks between a reflector direction and the BRDF's is shared by the pixels
// of an aligned 8x4 tile (the tile's first pixel's sample of that dimension), so the lanes of one SIMD vector or
// warp (a CPU driver's 8 pixels of a row, a GPU's 8x4) guide together or not at all: a guided ray traverses the
// reflector's geometry where most cosine rays escape to the sky, and one guided lane makes its whole vector wait.
// Each pixel's own estimate is unchanged in distribution (its choices are still uniform and independent of its
// other dimensions); only neighbours' choices are correlated. 0: each pixel draws its own.
#ifndef WB_REFLECTOR_COHERENT
#define WB_REFLECTOR_COHERENT 1
#endif

layout(set = 0, binding = WB_BIND_REFLECTORS, scalar) readonly buffer ReflectorBlock { vec4 reflectors[]; };

// The cone of reflector k's bounding sphere seen from x: its axis and the cosine of its half-angle. False when x
// is inside the sphere, the sphere lies wholly below the plane of ng, or the cone is too narrow for float.
bool reflectorCone(uint k, vec3 x, vec3 ng, out vec3 axis, out float cosMax) {
  const vec4 sphere = reflectors[k];
  const vec3 d = sphere.xyz - x;
  const float dist2 = dot(d, d);
  const float r2 = sphere.w * sphere.w;
  axis = vec3(0.0, 0.0, 1.0);
  cosMax = 1.0;
  if (!(dist2 > r2) || dot(d, ng) < -sphere.w) return false;
  axis = d * inversesqrt(dist2);
  cosMax = sqrt(1.0 - r2 / dist2);
  return cosMax < 1.0;
}

// The probability of a reflector direction at this vertex (0 without reflectors in view).
float reflectorFraction(SurfaceMaterial sm, vec3 ns, vec3 wo, uint visible) {
  return visible > 0u ? WB_REFLECTOR_FRACTION * brdfDiffuseProbability(sm, dot(ns, wo)) : 0.0;
}

// The reflectors x sees above its surface, and the sum over their cones that contain wi of the cone's uniform
// density (solid angle).
struct ReflectorView {
  uint visible;
  float conePdfSum;
};
ReflectorView reflectorView(vec3 x, vec3 ng, vec3 wi) {
  ReflectorView v;
  v.visible = 0u;
  v.conePdfSum = 0.0;
#if WB_REFLECTOR_GUIDING
  for (uint k = 0u; k < frame.reflectorCount; ++k) {
    vec3 axis;
    float cosMax;
    if (!reflectorCone(k, x, ng, axis, cosMax)) continue;
    ++v.visible;
    if (dot(wi, axis) >= cosMax) v.conePdfSum += sunConePdf(cosMax);
  }
#endif
  return v;
}

// The mixture's density for wi given the BRDF's: (1 - c) brdf + c (mean cone density over the visible reflectors).
float mixturePdf(float c, float brdf, ReflectorView v) {
  return c > 0.0 ? (1.0 - c) * brdf + c * v.conePdfSum / float(v.visible) : brdf;
}

// The mixture's density for wi (solid angle).
float pathPdf(SurfaceMaterial sm, vec3 ns, vec3 wo, vec3 x, vec3 ng, vec3 wi) {
  const float brdf = brdfPdf(sm, ns, wo, wi);
#if WB_REFLECTOR_GUIDING
  if (frame.reflectorCount > 0u) {
    const ReflectorView v = reflectorView(x, ng, wi);
    return mixturePdf(reflectorFraction(sm, ns, wo, v.visible), brdf, v);
  }
#endif
  return brdf;
}

// The probability that pathSample picked `lobe` (the path inspector's record).
float pathLobeProbability(SurfaceMaterial sm, vec3 ns, vec3 wo, vec3 x, vec3 ng, uint lobe) {
  const float c = reflectorFraction(sm, ns, wo, reflectorView(x, ng, vec3(0.0)).visible);
  const float pDiffuse = brdfDiffuseProbability(sm, dot(ns, wo));
  return lobe == WB_LOBE_REFLECTOR ? c : (1.0 - c) * (lobe == WB_LOBE_DIFFUSE ? pDiffuse : 1.0 - pDiffuse);
}

// The number that picks the part of the mixture at this vertex (pathSample's u.x) from sample dimension `dim`:
// the pixel's own `own`, or with WB_REFLECTOR_COHERENT its tile's (gSampler's pixel, rounded down to the tile).
float pathPartSample(uint dim, float own) {
#if WB_REFLECTOR_GUIDING && WB_REFLECTOR_COHERENT
  if (frame.reflectorCount > 0u) {
    const SamplerState tile =
        samplerInit(gSampler.pixel & ~uvec2(7u, 3u), gSampler.sampleIndex, gSampler.seed, gSampler.mode);
    return samplerGet1D(tile, dim);
  }
#endif
  return own;
}

// A continuation direction from the mixture; pdf and weight (brdfEval / pdf) are the mixture's. u.x picks the
// part (its remainder picks the reflector, or the BRDF's lobe), (u.y, u.z) the direction. A BRDF direction keeps
// the BRDF sample's own pdf and weight, rescaled to the mixture's; only a reflector direction evaluates the BRDF.
BrdfSample pathSample(SurfaceMaterial sm, vec3 ns, vec3 wo, vec3 x, vec3 ng, vec3 u) {
#if WB_REFLECTOR_GUIDING
  if (frame.reflectorCount > 0u) {
    const uint visible = reflectorView(x, ng, vec3(0.0)).visible;
    const float c = reflectorFraction(sm, ns, wo, visible);
    if (c > 0.0 && u.x < c) {
      BrdfSample s;
      const uint pick = min(uint(u.x / c * float(visible)), visible - 1u);
      uint seen = 0u;
      s.wi = ns;
      for (uint k = 0u; k < frame.reflectorCount; ++k) {
        vec3 axis;
        float cosMax;
        if (!reflectorCone(k, x, ng, axis, cosMax)) continue;
        if (seen++ == pick) s.wi = sampleCone(axis, cosMax, vec2(u.y, u.z));
      }
      s.lobe = WB_LOBE_REFLECTOR;
      s.pdf = mixturePdf(c, brdfPdf(sm, ns, wo, s.wi), reflectorView(x, ng, s.wi));
      s.weight = s.pdf > 0.0 ? brdfEval(sm, ns, wo, s.wi) / s.pdf : vec3(0.0);
      return s;
    }
    if (c > 0.0) {
      BrdfSample s = brdfSample(sm, ns, wo, vec3(min((u.x - c) / (1.0 - c), kOneMinusEpsilon), u.y, u.z));
      if (!(s.pdf > 0.0)) return s;
      const float pdf = mixturePdf(c, s.pdf, reflectorView(x, ng, s.wi));
      s.weight *= s.pdf / pdf;
      s.pdf = pdf;
      return s;
    }
  }
#endif
  return brdfSample(sm, ns, wo, u);
}

#endif
