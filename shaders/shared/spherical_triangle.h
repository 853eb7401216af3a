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

// ---- The streamlined technique (WB_EMITTER_SOLID_ANGLE=2, the default) ----
// The functions above are the plain technique (WB_EMITTER_SOLID_ANGLE=1). Those below compute the same
// distribution with less work: one set of unit vectors serves the solid angle and the sampler, the solid angle is
// computed once per light sample, the orthogonalisations need no fallback branches, and the sampled direction meets
// the light's plane by a plane intersection instead of a full ray-triangle test. Their rule
// (triangleLightUseSolidAngle) takes its ratio as a parameter and measures the distance to the centroid.

// The spherical triangle of (p0, p1, p2) seen from a point: unit vectors to the vertices, the cosines of the arcs
// a-b and c-a, and the solid angle (Van Oosterom and Strackee), 0 where the point lies on a vertex or in the
// triangle's plane.
struct SphericalTriangle {
  vec3 a;
  float cosAB;
  vec3 b;
  float omega;
  vec3 c;
  float cosCA;
};

WB_FN SphericalTriangle sphericalTriangleSetup(vec3 p, vec3 p0, vec3 p1, vec3 p2) {
  SphericalTriangle s;
  s.a = p0 - p;
  s.b = p1 - p;
  s.c = p2 - p;
  s.a *= inversesqrt(dot(s.a, s.a));  // a point on a vertex gives NaN here, and omega 0 below
  s.b *= inversesqrt(dot(s.b, s.b));
  s.c *= inversesqrt(dot(s.c, s.c));
  s.cosAB = dot(s.a, s.b);
  s.cosCA = dot(s.c, s.a);
  float triple = abs(dot(s.a, cross(s.b, s.c)));
  float omega = 2.0f * atan(triple, 1.0f + s.cosAB + dot(s.b, s.c) + s.cosCA);
  s.omega = omega > 0.0f ? omega : 0.0f;
  return s;
}

// A direction uniformly distributed over the spherical triangle (pdf 1 / t.omega; t.omega > 0): Arvo's
// algorithm, u.x picks the area of the sub-triangle (a, b, c'), u.y the point on the arc b-c'. The angle at a
// comes from the normals of the arcs a-b and a-c, its sine from its cosine: Arvo's formula for c' needs the two
// consistent (sin^2 + cos^2 = 1) more than each exact, and an independently computed sine (the triple product)
// made seen-at-a-grazing-angle triangles' directions less precise.
WB_FN vec3 sphericalTriangleSample(SphericalTriangle t, vec2 u) {
  vec3 nab = cross(t.a, t.b);
  vec3 nac = cross(t.a, t.c);
  float inv = inversesqrt(dot(nab, nab) * dot(nac, nac));
  float cosAlpha = clamp(dot(nab, nac) * inv, -1.0f, 1.0f);
  float sinAlpha = sqrt(max(0.0f, 1.0f - cosAlpha * cosAlpha));
  // c' on the arc a-c at cos(arc a-c') = q, such that (a, b, c') has area u.x * omega.
  float areaPrime = u.x * t.omega;
  float sinArea = sin(areaPrime);
  float cosArea = cos(areaPrime);
  float s = sinArea * cosAlpha - cosArea * sinAlpha;  // sin(areaPrime - alpha)
  float r = cosArea * cosAlpha + sinArea * sinAlpha;  // cos(areaPrime - alpha)
  float uu = r - cosAlpha;
  float vv = s + sinAlpha * t.cosAB;
  float denominator = (vv * s + uu * r) * sinAlpha;
  float q = denominator != 0.0f ? ((vv * r - uu * s) * cosAlpha - vv) / denominator : 1.0f;
  q = clamp(q, -1.0f, 1.0f);
  vec3 ca = t.c - t.cosCA * t.a;  // along the arc a-c, orthogonal to a (|ca| = sin(arc a-c) > 0 for omega > 0)
  vec3 cPrime = q * t.a + (sqrt(max(0.0f, 1.0f - q * q)) * inversesqrt(dot(ca, ca))) * ca;
  // On the arc b-c' at cos = z = 1 - u.y (1 - cos(b, c')): 1 - z^2 = (1 - z)(1 + z) without cancellation.
  float cosBCPrime = dot(cPrime, t.b);
  float oneMinusZ = u.y * (1.0f - cosBCPrime);
  vec3 cb = cPrime - cosBCPrime * t.b;
  float sinZ = sqrt(max(0.0f, oneMinusZ * (2.0f - oneMinusZ)));
  float l2 = dot(cb, cb);
  return normalize((1.0f - oneMinusZ) * t.b + (l2 > 0.0f ? sinZ * inversesqrt(l2) : 0.0f) * cb);
}

// The technique rule with its ratio: solid angle where the longest edge times `ratio` is longer than the
// distance from p to the triangle's centroid, i.e. where the triangle subtends a large angle. (The plain
// technique's rule, the distance to the triangle's plane, also picks solid angle for far points near that
// plane, where the spherical triangle is a thin sliver: little gain, and float precision suffers.) A
// function of the point and the triangle alone, so next-event estimation and the MIS weight of a BRDF sample
// that hits the light agree on the technique. n = cross(p1 - p0, p2 - p0): degenerate triangles never qualify.
WB_FN bool triangleLightUseSolidAngle(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec3 n, float ratio) {
  vec3 e0 = p1 - p0;
  vec3 e1 = p2 - p1;
  vec3 e2 = p0 - p2;
  float longest2 = max(dot(e0, e0), max(dot(e1, e1), dot(e2, e2)));
  vec3 d = (p0 + p1 + p2) * (1.0f / 3.0f) - p;
  return dot(n, n) > 0.0f && longest2 * (ratio * ratio) > dot(d, d);
}

// A direction towards triangle light (p0, p1, p2) from p, by the technique the rule picks, with its solid-angle
// pdf (for a triangle chosen with probability 1): 1 / omega, or for a uniform point of the area d^2 / (A cos).
// pdf 0: no sample (p in the plane or on a vertex, or the point seen edge-on).
struct TriangleLightSample {
  vec3 wi;        // unit direction from p
  float dist;     // distance to the light's point
  vec3 position;  // the point on the light
  float pdf;
  vec3 normal;    // unit geometric normal (winding order)
  float cosLight; // |dot(normal, wi)|
  float area;
};

WB_FN TriangleLightSample triangleLightSample(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec2 u, float ratio) {
  TriangleLightSample s;
  s.pdf = 0.0f;
  vec3 e1 = p1 - p0;
  vec3 e2 = p2 - p0;
  vec3 n = cross(e1, e2);
  float invLength = inversesqrt(dot(n, n));
  s.normal = n * invLength;
  s.area = 0.5f / invLength;
  if (triangleLightUseSolidAngle(p, p0, p1, p2, n, ratio)) {
    SphericalTriangle t = sphericalTriangleSetup(p, p0, p1, p2);
    if (!(t.omega > 0.0f)) return s;
    s.wi = sphericalTriangleSample(t, u);
    // Where the direction meets the light's plane.
    float cosN = dot(s.normal, s.wi);
    s.dist = dot(s.normal, p0 - p) / cosN;
    s.position = p + s.dist * s.wi;
    s.cosLight = abs(cosN);
    if (s.dist > 0.0f) s.pdf = 1.0f / t.omega;  // else: edge-on, rounding
  } else {
    float su = sqrt(u.x);
    s.position = (1.0f - su) * p0 + (su * (1.0f - u.y)) * p1 + (su * u.y) * p2;
    vec3 d = s.position - p;
    float dist2 = dot(d, d);
    float invDist = inversesqrt(dist2);
    s.dist = dist2 * invDist;
    s.wi = d * invDist;
    s.cosLight = abs(dot(s.normal, s.wi));
    if (dist2 > 0.0f && s.cosLight > 0.0f) s.pdf = dist2 / (s.area * s.cosLight);
  }
  return s;
}

// The solid-angle pdf with which triangleLightSample picks the direction from p to a point of the triangle at
// distance dist, seen at cosLight (= |dot(unit normal, direction)|): what MIS evaluates for a BRDF sample that hits
// the light.
WB_FN float triangleLightPdf(vec3 p, vec3 p0, vec3 p1, vec3 p2, float dist, float cosLight, float ratio) {
  vec3 n = cross(p1 - p0, p2 - p0);
  if (triangleLightUseSolidAngle(p, p0, p1, p2, n, ratio)) {
    float omega = sphericalTriangleSetup(p, p0, p1, p2).omega;
    return omega > 0.0f ? 1.0f / omega : 0.0f;
  }
  float area = 0.5f * length(n);
  return area > 0.0f && cosLight > 0.0f ? dist * dist / (area * cosLight) : 0.0f;
}

WB_NAMESPACE_END

#endif
