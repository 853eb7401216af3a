// Sampling a triangle light by the solid angle it subtends (Arvo 1995, "Stratified Sampling of Spherical
// Triangles", SIGGRAPH '95), shared by the shaders and the CPU tests.
//
// Uniform area sampling of a triangle gives directions with density d^2 / (A cos(theta_light)): near a large light
// (a wall next to the Cornell box's ceiling light) that varies by orders of magnitude over the light, and so does
// the estimator. Sampling the spherical triangle the light projects to makes the density uniform, 1 / Omega, so
// only the receiver's cosine and the BRDF vary. For small or distant triangles the two are alike, and the spherical
// formulas lose precision (the area is a difference of nearly equal angles), so callers pick the technique with
// sphericalTriangleUseSolidAngle: solid angle where the longest edge is longer than half the distance to the
// triangle's plane (Cycles uses the whole distance; half reaches the Cornell box's floor and lowered its relMSE a
// little more, 0.01336 -> 0.01319 at 32 spp). It is a function of the point and the triangle alone, so the pdf
// that MIS evaluates for a BRDF sample that hits the light is the pdf of the technique sampling used there.
#ifndef WB_SPHERICAL_TRIANGLE_H
#define WB_SPHERICAL_TRIANGLE_H
#include "sampling_math.h"

WB_NAMESPACE_BEGIN

// True where the triangle (p0, p1, p2) is sampled by solid angle from point p: longest edge > half the distance
// to its plane (see the header comment).
WB_FN bool sphericalTriangleUseSolidAngle(vec3 p, vec3 p0, vec3 p1, vec3 p2) {
  vec3 e0 = p1 - p0;
  vec3 e1 = p2 - p1;
  vec3 e2 = p0 - p2;
  float longest2 = max(dot(e0, e0), max(dot(e1, e1), dot(e2, e2)));
  vec3 n = cross(e0, p2 - p0);
  float n2 = dot(n, n);
  if (!(n2 > 0.0f)) return false;
  float planeDistance = dot(n, p0 - p);  // times |n|
  return longest2 * n2 * 4.0f > planeDistance * planeDistance;
}

// Solid angle of the triangle seen from p (Van Oosterom and Strackee 1983), in [0, 2 pi]; 0 when p lies in the
// triangle's plane or on a vertex.
WB_FN float sphericalTriangleSolidAngle(vec3 p, vec3 p0, vec3 p1, vec3 p2) {
  vec3 a = p0 - p;
  vec3 b = p1 - p;
  vec3 c = p2 - p;
  float la = length(a);
  float lb = length(b);
  float lc = length(c);
  if (!(la > 0.0f && lb > 0.0f && lc > 0.0f)) return 0.0f;
  a /= la;
  b /= lb;
  c /= lc;
  float numerator = abs(dot(a, cross(b, c)));
  float denominator = 1.0f + dot(a, b) + dot(b, c) + dot(c, a);
  float omega = 2.0f * atan(numerator, denominator);
  return omega > 0.0f ? omega : 0.0f;
}

// Unit vector along the part of v orthogonal to unit vector n (a fallback orthogonal to n where v is parallel).
WB_FN vec3 sphericalTriangleOrthogonal(vec3 v, vec3 n) {
  vec3 w = v - dot(v, n) * n;
  float l2 = dot(w, w);
  if (l2 > 1.0e-30f) return w * inversesqrt(l2);
  vec3 t;
  vec3 b;
  buildOrthonormalBasis(n, t, b);
  return t;
}

// A direction uniformly distributed over the solid angle of triangle (p0, p1, p2) seen from p (Arvo's algorithm:
// u.x picks the sub-triangle area, u.y the point along the arc), so pdf = 1 / omega (omega: solidAngle). Returns
// (0, 0, 0) when the triangle has no solid angle from p.
WB_FN vec3 sampleSphericalTriangle(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec2 u, float omega) {
  if (!(omega > 0.0f)) return vec3(0.0f);
  vec3 a = normalize(p0 - p);
  vec3 b = normalize(p1 - p);
  vec3 c = normalize(p2 - p);
  // Internal angle at a (between the great circles a-b and a-c) from the normals of their planes.
  vec3 nab = cross(a, b);
  vec3 nac = cross(a, c);
  float lab = length(nab);
  float lac = length(nac);
  if (!(lab > 0.0f && lac > 0.0f)) return vec3(0.0f);
  float cosAlpha = clamp(dot(nab, nac) / (lab * lac), -1.0f, 1.0f);
  float sinAlpha = sqrt(max(0.0f, 1.0f - cosAlpha * cosAlpha));
  float cosC = dot(a, b);  // cosine of the arc a-b
  // The sub-triangle (a, b, c') of area u.x * omega: c' on the arc a-c at cos(arc a-c') = q.
  float areaPrime = u.x * omega;
  float sinArea = sin(areaPrime);
  float cosArea = cos(areaPrime);
  float s = sinArea * cosAlpha - cosArea * sinAlpha;  // sin(areaPrime - alpha)
  float t = cosArea * cosAlpha + sinArea * sinAlpha;  // cos(areaPrime - alpha)
  float uu = t - cosAlpha;
  float vv = s + sinAlpha * cosC;
  float denominator = (vv * s + uu * t) * sinAlpha;
  float q = denominator != 0.0f ? ((vv * t - uu * s) * cosAlpha - vv) / denominator : 1.0f;
  q = clamp(q, -1.0f, 1.0f);
  vec3 cPrime = q * a + sqrt(max(0.0f, 1.0f - q * q)) * sphericalTriangleOrthogonal(c, a);
  // A point on the arc b-c' with the density that makes the whole uniform.
  float z = 1.0f - u.y * (1.0f - dot(cPrime, b));
  z = clamp(z, -1.0f, 1.0f);
  return normalize(z * b + sqrt(max(0.0f, 1.0f - z * z)) * sphericalTriangleOrthogonal(cPrime, b));
}

// Barycentric coordinates (of p1, p2) and distance of the hit of the ray p + t dir with the triangle's plane
// (Moeller-Trumbore), clamped into the triangle: where a sampled direction meets the light. Returns t <= 0 when the
// ray is parallel to the plane.
WB_FN vec3 sphericalTriangleHit(vec3 p, vec3 dir, vec3 p0, vec3 p1, vec3 p2) {
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 s1 = cross(dir, e2);
  float divisor = dot(s1, e1);
  if (divisor == 0.0f) return vec3(0.0f, 0.0f, -1.0f);
  float inv = 1.0f / divisor;
  vec3 d = p - p0;
  vec3 s2 = cross(d, e1);
  float b1 = clamp(dot(d, s1) * inv, 0.0f, 1.0f);
  float b2 = clamp(dot(dir, s2) * inv, 0.0f, 1.0f);
  float sum = b1 + b2;
  if (sum > 1.0f) {
    b1 /= sum;
    b2 /= sum;
  }
  return vec3(b1, b2, dot(e2, s2) * inv);
}

WB_NAMESPACE_END

#endif
