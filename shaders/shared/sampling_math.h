// Sampling helpers shared by the shaders and the CPU tests (GLSL 460 and C++20 via glsl_cpp.h).
// Conventions:
//  - Local shading frame: +Z is the normal; buildOrthonormalBasis(n, t, b) gives t, b with t x b = n
//    (Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1)).
//  - All direction arguments are unit vectors; wo points away from the surface (towards the viewer),
//    wi points away from the surface (towards the light).
//  - GGX uses alpha = roughness^2, isotropic; ggxAlpha() clamps alpha to WB_MIN_ALPHA so roughness 0 stays finite.
//  - Equirectangular mapping (environment maps), with an optional rotation of the map about +Y:
//      d' = rotateY(d, -rotation)                           (world -> map space)
//      u  = 0.5 + atan(d'.x, -d'.z) / (2 pi)                (u = 0.5 is -Z, u grows towards +X; seam at +Z)
//      v  = acos(d'.y) / pi                                 (v = 0 is +Y: row 0 = top of the image)
//    so uvToDirection((u, v)) = rotateY((sin(theta) sin(phi), cos(theta), -sin(theta) cos(phi)), rotation)
//    with phi = (u - 0.5) 2 pi, theta = v pi. A positive rotation turns the map counter-clockwise seen from +Y.
#ifndef WB_SAMPLING_MATH_H
#define WB_SAMPLING_MATH_H
#include "glsl_cpp.h"

WB_NAMESPACE_BEGIN

WB_CONST float kPi = 3.14159265358979f;
WB_CONST float kTwoPi = 6.28318530717959f;
WB_CONST float kInvPi = 0.318309886183791f;
WB_CONST float kInvTwoPi = 0.159154943091895f;
WB_CONST float kOneMinusEpsilon = 0.99999994f;  // largest float below 1 (0x1.fffffep-1)
WB_CONST float kMinGgxAlpha = 1.0e-4f;         // alpha floor: roughness 0 -> very sharp but finite GGX lobe

// Rec. 709 / sRGB-primaries luminance of linear RGB.
WB_FN float luminance(vec3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

WB_FN float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Duff et al. 2017 branchless orthonormal basis; n must be unit length (a zero n yields t = +X, b = +Y).
WB_FN void buildOrthonormalBasis(vec3 n, OUT(vec3) t, OUT(vec3) b) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}
WB_FN vec3 toLocal(vec3 v, vec3 t, vec3 b, vec3 n) { return vec3(dot(v, t), dot(v, b), dot(v, n)); }
WB_FN vec3 toWorld(vec3 v, vec3 t, vec3 b, vec3 n) { return v.x * t + v.y * b + v.z * n; }

// ---- cosine-weighted hemisphere (concentric disk mapping, Shirley & Chiu 1997) ----
WB_FN vec2 sampleConcentricDisk(vec2 u) {
  float ax = 2.0f * u.x - 1.0f;
  float ay = 2.0f * u.y - 1.0f;
  if (ax == 0.0f && ay == 0.0f) return vec2(0.0f, 0.0f);
  float r;
  float phi;
  if (abs(ax) > abs(ay)) {
    r = ax;
    phi = 0.25f * kPi * (ay / ax);
  } else {
    r = ay;
    phi = 0.5f * kPi - 0.25f * kPi * (ax / ay);
  }
  return vec2(r * cos(phi), r * sin(phi));
}
// Local frame, +Z up; pdf = cos(theta) / pi (cosineHemispherePdf). z may be 0 on the disk rim: treat pdf 0 as invalid.
WB_FN vec3 sampleCosineHemisphere(vec2 u) {
  vec2 d = sampleConcentricDisk(u);
  float z = sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return vec3(d.x, d.y, z);
}
WB_FN float cosineHemispherePdf(float cosTheta) { return max(cosTheta, 0.0f) * kInvPi; }

// Uniform sphere (used by tests and the constant environment fallback); pdf = 1 / (4 pi).
WB_FN vec3 sampleUniformSphere(vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = sqrt(max(0.0f, 1.0f - z * z));
  float phi = kTwoPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

// ---- GGX (Trowbridge-Reitz), isotropic, local frame ----
WB_FN float ggxAlpha(float roughness) {
  float r = clamp(roughness, 0.0f, 1.0f);
  return max(r * r, kMinGgxAlpha);
}
// Normal distribution D(h); h in the local frame (h.z = cos theta_h). Written with h.x, h.y so it stays accurate
// for tiny alpha (no 1 - cos^2 cancellation).
WB_FN float ggxD(vec3 h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  float t = (h.x * h.x + h.y * h.y) / a2 + h.z * h.z;
  return 1.0f / (kPi * a2 * t * t);
}
// Smith G1 for GGX (cosTheta > 0).
WB_FN float ggxG1(float cosTheta, float alpha) {
  float a2 = alpha * alpha;
  return 2.0f * cosTheta / (cosTheta + sqrt(a2 + (1.0f - a2) * cosTheta * cosTheta));
}
// Height-correlated Smith visibility V = G2 / (4 |n.l| |n.v|) (glTF appendix B); both cosines > 0.
WB_FN float ggxVisibilitySmithHC(float NdotV, float NdotL, float alpha) {
  float a2 = alpha * alpha;
  float gv = NdotL * sqrt(NdotV * NdotV * (1.0f - a2) + a2);
  float gl = NdotV * sqrt(NdotL * NdotL * (1.0f - a2) + a2);
  float s = gv + gl;
  return s > 0.0f ? 0.5f / s : 0.0f;
}
// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4): a microfacet normal h with density
// D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z. wo in the local frame with wo.z > 0.
WB_FN vec3 sampleGgxVndf(vec3 wo, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lensq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(lensq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = kTwoPi * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));
}
// Density of h from sampleGgxVndf.
WB_FN float ggxVndfPdf(vec3 wo, vec3 h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return ggxG1(wo.z, alpha) * max(0.0f, dot(wo, h)) * ggxD(h, alpha) / wo.z;
}
// Solid-angle density of wi = reflect(-wo, h) for h ~ VNDF: D(h) G1(wo) / (4 wo.z), written without 1/wo.z.
WB_FN float ggxReflectionPdf(vec3 wo, vec3 h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  return ggxD(h, alpha) / (2.0f * (wo.z + sqrt(a2 + (1.0f - a2) * wo.z * wo.z)));
}
WB_FN vec3 reflectAbout(vec3 wo, vec3 h) { return 2.0f * dot(wo, h) * h - wo; }

// ---- multiple importance sampling ----
// Power heuristic (beta = 2) weight of strategy a: (nA pdfA)^2 / ((nA pdfA)^2 + (nB pdfB)^2); overflow-safe.
WB_FN float powerHeuristic(float nA, float pdfA, float nB, float pdfB) {
  float a = nA * pdfA;
  float b = nB * pdfB;
  if (!(a > 0.0f)) return 0.0f;
  if (!(b > 0.0f)) return 1.0f;
  if (a >= b) {
    float r = b / a;
    return 1.0f / (1.0f + r * r);
  }
  float r = a / b;
  return r * r / (1.0f + r * r);
}

// ---- equirectangular mapping (see the header comment for the convention) ----
WB_FN vec3 rotateY(vec3 d, float angle) {
  float c = cos(angle);
  float s = sin(angle);
  return vec3(c * d.x + s * d.z, d.y, -s * d.x + c * d.z);
}
// u in [0,1], v in [0,1]; row 0 (v = 0) is +Y.
WB_FN vec2 directionToEquirect(vec3 dir, float rotation) {
  vec3 d = rotateY(dir, -rotation);
  float u = 0.5f + atan(d.x, -d.z) * kInvTwoPi;
  float v = acos(clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return vec2(u, v);
}
WB_FN vec3 equirectToDirection(vec2 uv, float rotation) {
  float phi = (uv.x - 0.5f) * kTwoPi;
  float theta = uv.y * kPi;
  float st = sin(theta);
  vec3 d = vec3(st * sin(phi), cos(theta), -st * cos(phi));
  return rotateY(d, rotation);
}

// ---- robust ray origins: Waechter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection",
// Ray Tracing Gems ch. 6. p: hit point, n: geometric normal on the side the new ray leaves from
// (flip it for transmission / back faces). Offsets in ULPs far from the origin, by a tiny fixed amount near it.
WB_FN vec3 offsetRay(vec3 p, vec3 n) {
  WB_CONST float kOrigin = 1.0f / 32.0f;
  WB_CONST float kFloatScale = 1.0f / 65536.0f;
  WB_CONST float kIntScale = 256.0f;
  ivec3 ofi = ivec3(int(kIntScale * n.x), int(kIntScale * n.y), int(kIntScale * n.z));
  vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0f ? -ofi.x : ofi.x)),
                 intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0f ? -ofi.y : ofi.y)),
                 intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0f ? -ofi.z : ofi.z)));
  return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : pi.x,
              abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : pi.y,
              abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : pi.z);
}

WB_NAMESPACE_END

#endif
