// glTF 2.0 metallic-roughness BRDF (specification appendix B) with KHR_materials_specular, shared by the shaders
// and the CPU tests. Everything here is in terms of unit vectors pointing away from the surface.
//
// Model (h = normalize(wo + wi), VdotH = wo.h, alpha = ggxAlpha(roughness) = max(roughness^2, 1e-4)):
//   F_d        = F0_d + (1 - F0_d) (1 - VdotH)^5,  F0_d = min(0.04 * specularColor, 1)          (per channel)
//   dielectric = (1 - specularFactor * max(F_d)) * baseColor / pi + specularFactor * F_d * D * V
//                (this is F0 = min(0.04 specularColor, 1) * specularFactor, F90 = specularFactor, and the
//                 diffuse weight 1 - specularFactor * max(F) of KHR_materials_specular)
//   metal      = F_m * D * V,  F_m = baseColor + (1 - baseColor) (1 - VdotH)^5
//   f          = mix(dielectric, metal, metallic)
// D = GGX, V = height-correlated Smith visibility G2 / (4 n.wo n.wi).
//
// brdfEval returns f * cos(theta_i) (= f * wi.z), i.e. the integrand of the reflected radiance; zero when wo or wi
// is at or below the surface (callers flip n for double-sided / back-face hits before calling).
//
// Sampling: two lobes, chosen with u.x.
//   pDiffuseDielectric = 1 - clamp(luminance(specularFactor * F_schlick(F0_d, 1, n.wo)), 0.01, 0.99)
//                        (1 when specularFactor = 0: without a specular layer there is no lobe to sample)
//   pDiffuse           = (1 - metallic) * pDiffuseDielectric,   pSpecular = 1 - pDiffuse
// so a pure metal (metallic = 1) never picks the diffuse lobe (it has none), a dielectric picks the specular lobe
// with its view-angle Fresnel reflectance, and metallic in (0,1) linearly blends the two probabilities.
// Specular: GGX visible normals (Heitz 2018), wi = reflect(-wo, h). Diffuse: cosine hemisphere (concentric map).
// brdfPdf is the combined one-sample-MIS density pSpecular * pdf_ggx + pDiffuse * pdf_cos, exactly what
// brdfSample draws from, and the sample weight is brdfEval / brdfPdf (never the single-lobe pdf).
#ifndef WB_BRDF_H
#define WB_BRDF_H
#include "sampling_math.h"

WB_NAMESPACE_BEGIN

// Evaluated surface material (after textures). Not a GPU-buffer struct: layout is irrelevant.
struct SurfaceMaterial {
  vec3 baseColor;       // linear RGB
  float metallic;       // [0,1]
  float roughness;      // perceptual roughness [0,1]; alpha = roughness^2
  float specularFactor; // KHR_materials_specular specularFactor (1 when absent)
  vec3 specularColor;   // KHR_materials_specular specularColorFactor (1 when absent)
};

// Result of brdfSample. pdf == 0 marks an invalid sample (wi below the surface / wo below): terminate the path.
struct BrdfSample {
  vec3 wi;      // sampled direction (world space in brdfSample, local in brdfSampleLocal)
  float pdf;    // combined pdf brdfPdf(wo, wi) (solid angle)
  vec3 weight;  // brdfEval / pdf = f * cos / pdf
  uint lobe;    // WB_LOBE_DIFFUSE or WB_LOBE_SPECULAR (the lobe that generated wi)
};

#define WB_LOBE_DIFFUSE 0u
#define WB_LOBE_SPECULAR 1u
#define WB_LOBE_REFLECTOR 2u  // the path tracer's direction towards a glossy reflector (pathtracer/guiding.glsl)

WB_FN SurfaceMaterial makeSurfaceMaterial(vec3 baseColor, float metallic, float roughness) {
  SurfaceMaterial m;
  m.baseColor = baseColor;
  m.metallic = metallic;
  m.roughness = roughness;
  m.specularFactor = 1.0f;
  m.specularColor = vec3(1.0f);
  return m;
}

WB_FN vec3 fresnelSchlick(vec3 f0, float f90, float cosTheta) {
  float c = clamp(1.0f - cosTheta, 0.0f, 1.0f);
  float c2 = c * c;
  float c5 = c2 * c2 * c;
  return f0 + (vec3(f90) - f0) * c5;
}

WB_FN vec3 dielectricF0(SurfaceMaterial m) { return min(0.04f * m.specularColor, vec3(1.0f)); }

// Probability of the diffuse lobe for a view direction with cos(theta_o) = NdotV (see header comment).
WB_FN float brdfDiffuseProbability(SurfaceMaterial m, float NdotV) {
  float fd = luminance(m.specularFactor * fresnelSchlick(dielectricF0(m), 1.0f, NdotV));
  float pDiffDielectric = 1.0f - (m.specularFactor > 0.0f ? clamp(fd, 0.01f, 0.99f) : 0.0f);
  return (1.0f - clamp(m.metallic, 0.0f, 1.0f)) * pDiffDielectric;
}

// f * cos(theta_i) in the local frame (+Z = normal).
WB_FN vec3 brdfEvalLocal(SurfaceMaterial m, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(wo + wi);
  float VdotH = max(dot(wo, h), 0.0f);
  float alpha = ggxAlpha(m.roughness);
  float dv = ggxD(h, alpha) * ggxVisibilitySmithHC(wo.z, wi.z, alpha);
  vec3 fd = fresnelSchlick(dielectricF0(m), 1.0f, VdotH);
  vec3 dielectric = (1.0f - m.specularFactor * maxComponent(fd)) * m.baseColor * kInvPi +
                    m.specularFactor * fd * dv;
  vec3 metal = fresnelSchlick(m.baseColor, 1.0f, VdotH) * dv;
  float metallic = clamp(m.metallic, 0.0f, 1.0f);
  return (dielectric * (1.0f - metallic) + metal * metallic) * wi.z;
}

// Combined solid-angle pdf of brdfSampleLocal.
WB_FN float brdfPdfLocal(SurfaceMaterial m, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  float pDiff = brdfDiffuseProbability(m, wo.z);
  vec3 h = normalize(wo + wi);
  float alpha = ggxAlpha(m.roughness);
  return (1.0f - pDiff) * ggxReflectionPdf(wo, h, alpha) + pDiff * wi.z * kInvPi;
}

// u: three uniform numbers in [0,1): u.x lobe choice, (u.y, u.z) direction.
WB_FN BrdfSample brdfSampleLocal(SurfaceMaterial m, vec3 wo, vec3 u) {
  BrdfSample s;
  s.wi = vec3(0.0f, 0.0f, 1.0f);
  s.pdf = 0.0f;
  s.weight = vec3(0.0f);
  s.lobe = WB_LOBE_DIFFUSE;
  if (wo.z <= 0.0f) return s;
  float pDiff = brdfDiffuseProbability(m, wo.z);
  if (u.x < pDiff) {
    s.wi = sampleCosineHemisphere(vec2(u.y, u.z));
  } else {
    vec3 h = sampleGgxVndf(wo, ggxAlpha(m.roughness), vec2(u.y, u.z));
    s.wi = reflectAbout(wo, h);
    s.lobe = WB_LOBE_SPECULAR;
  }
  if (s.wi.z <= 0.0f) return s;
  s.wi = normalize(s.wi);
  float pdf = brdfPdfLocal(m, wo, s.wi);
  if (!(pdf > 0.0f)) return s;
  s.pdf = pdf;
  s.weight = brdfEvalLocal(m, wo, s.wi) / pdf;
  return s;
}

// World-space wrappers; n is the (shading) normal on wo's side.
WB_FN vec3 brdfEval(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
  vec3 t;
  vec3 b;
  buildOrthonormalBasis(n, t, b);
  return brdfEvalLocal(m, toLocal(wo, t, b, n), toLocal(wi, t, b, n));
}
WB_FN float brdfPdf(SurfaceMaterial m, vec3 n, vec3 wo, vec3 wi) {
  vec3 t;
  vec3 b;
  buildOrthonormalBasis(n, t, b);
  return brdfPdfLocal(m, toLocal(wo, t, b, n), toLocal(wi, t, b, n));
}
WB_FN BrdfSample brdfSample(SurfaceMaterial m, vec3 n, vec3 wo, vec3 u) {
  vec3 t;
  vec3 b;
  buildOrthonormalBasis(n, t, b);
  BrdfSample s = brdfSampleLocal(m, toLocal(wo, t, b, n), u);
  s.wi = toWorld(s.wi, t, b, n);
  return s;
}

WB_NAMESPACE_END

#endif
