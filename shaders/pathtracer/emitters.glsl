// Area lights: sampling the scene's emissive triangles (alias table over luminance * area; then the triangle's solid
// angle, Arvo 1995, or a point of its area) and the matching solid-angle pdf, also evaluated when a BRDF-sampled
// ray happens to hit an emitter (for MIS).
#ifndef WB_PT_EMITTERS_GLSL
#define WB_PT_EMITTERS_GLSL
#include "../shared/spherical_triangle.h"

// How a picked triangle is sampled (--define WB_EMITTER_SOLID_ANGLE=N):
//  2 (the default): by solid angle where the triangle is large from the shading point (its longest edge times
//    WB_EMITTER_SOLID_ANGLE_RATIO is longer than the distance to its centroid), else a uniform point of its area,
//    with the streamlined sampler of shared/spherical_triangle.h (triangleLightSample); a single-sided emitter seen
//    from behind gets no sample at all.
//  1: the plain technique: solid angle where the longest edge is longer than half the distance to the
//    triangle's plane (sphericalTriangleUseSolidAngle), with the plain sampler.
//  0: a uniform point of the area everywhere.
// Ratio 1.5 picks solid angle for nearly all of a Cornell box's wall area (the floor's far corners excepted): the
// error per sample of technique 1 at less work; a smaller ratio gives up some of it for no time saved on a GPU,
// where a warp pays for the technique if one of its paths takes it (docs/reports/error_per_sample.md).
#ifndef WB_EMITTER_SOLID_ANGLE
#define WB_EMITTER_SOLID_ANGLE 2
#endif
#ifndef WB_EMITTER_SOLID_ANGLE_RATIO
#define WB_EMITTER_SOLID_ANGLE_RATIO 1.5
#endif

layout(set = 0, binding = WB_BIND_EMITTERS, scalar) readonly buffer EmitterBlock { EmissiveTriangle emitters[]; };
layout(set = 0, binding = WB_BIND_EMITTER_ALIAS, scalar) readonly buffer EmitterAliasBlock {
  EnvAliasEntry emitterAlias[];
};

float emitterLuminance(vec3 emissiveFactor) { return luminance(emissiveFactor); }

// Area-measure pdf of a point on an emitter of this emissive factor (selection * 1 / area: the area cancels).
float emitterAreaPdf(vec3 emissiveFactor) {
  return frame.emitterTotalPower > 0.0 ? emitterLuminance(emissiveFactor) / frame.emitterTotalPower : 0.0;
}

// Solid-angle pdf with which sampleEmitter picks the direction from `origin` to a point of emitter triangle
// (p0, p1, p2) at distance dist, seeing the emitter at cosLight: the triangle's selection probability times the
// pdf of the technique sampleEmitter uses for this origin and triangle: 1 / solid angle, or the area pdf converted
// to solid angle (d^2 / (area cos)). Next-event estimation and the MIS weight of a BRDF sample that hits the
// emitter both evaluate this (or, in sampleEmitter, the same terms), so they agree.
float emitterPdf(vec3 origin, vec3 p0, vec3 p1, vec3 p2, vec3 emissiveFactor, float dist, float cosLight) {
  const float areaPdf = emitterAreaPdf(emissiveFactor);  // selection probability / area
#if WB_EMITTER_SOLID_ANGLE == 2
  const vec3 n = cross(p1 - p0, p2 - p0);
  const float area = 0.5 / inversesqrt(dot(n, n));
  return areaPdf * area * triangleLightPdf(origin, p0, p1, p2, dist, cosLight, float(WB_EMITTER_SOLID_ANGLE_RATIO));
#else
#if WB_EMITTER_SOLID_ANGLE == 1
  if (sphericalTriangleUseSolidAngle(origin, p0, p1, p2)) {
    const float omega = sphericalTriangleSolidAngle(origin, p0, p1, p2);
    const float area = 0.5 * length(cross(p1 - p0, p2 - p0));
    return omega > 0.0 ? areaPdf * area / omega : 0.0;
  }
#endif
  return areaPdf * dist * dist / max(cosLight, 1e-8);
#endif
}

// Barycentric coordinates of point x of triangle (p0, p1, p2) (for the emissive texture's uv).
vec3 emitterBarycentrics(vec3 x, vec3 p0, vec3 p1, vec3 p2) {
  const vec3 e1 = p1 - p0, e2 = p2 - p0, d = x - p0;
  const vec3 n = cross(e1, e2);
  const float inv = 1.0 / dot(n, n);
  const float b1 = dot(cross(d, e2), n) * inv;
  const float b2 = dot(cross(e1, d), n) * inv;
  return vec3(1.0 - b1 - b2, b1, b2);
}

struct EmitterSample {
  vec3 position;
  vec3 normal;   // geometric normal of the triangle (winding order)
  vec3 radiance; // emitted radiance towards the shading point (0 when it sees the back of a single-sided one)
  float pdf;     // solid-angle pdf at the shading point (0 = invalid)
  float dist;
  vec3 wi;
#if WB_INSPECT
  uint index;    // the emissive triangle (for the path inspector's records)
#endif
};

// Emitter counts up to this pick the alias table entry with the point's first number (the remainder keeps at
// least 16 bits for the point): selection and point are then stratified together, each triangle of a quad light
// getting its own stratified half of the sampler's 2D points. More emitters use a number of their own.
#define WB_EMITTER_SELECT_BY_POINT_MAX 256u

// A light sample from point p: uSelect picks the alias table entry (when there are more than
// WB_EMITTER_SELECT_BY_POINT_MAX emitters), uCoin the alias coin, u the direction (the sampler's best-stratified
// pair, see WB_DIM_LIGHT in shared/random.h): uniform over the triangle's solid angle where it is large from p,
// else a uniform point of its area (emitterPdf).
EmitterSample sampleEmitter(vec3 p, float uSelect, float uCoin, vec2 u) {
  EmitterSample s;
  s.pdf = 0.0;
  s.radiance = vec3(0.0);
  const uint n = frame.emitterCount;
  uint i;
  if (n <= WB_EMITTER_SELECT_BY_POINT_MAX) {
    const float scaled = u.x * float(n);
    i = min(uint(scaled), n - 1u);
    u.x = min(scaled - float(i), 0.99999994);
  } else {
    i = min(uint(uSelect * float(n)), n - 1u);
  }
  const EnvAliasEntry e = emitterAlias[i];
  if (uCoin >= e.prob) i = e.alias;
  const EmissiveTriangle t = emitters[i];
#if WB_INSPECT
  s.index = i;
#endif
#if WB_EMITTER_SOLID_ANGLE == 2
  // A single-sided emitter seen from behind (or edge-on) is black from p: no sample.
  if (t.doubleSided == 0u && dot(cross(t.p1 - t.p0, t.p2 - t.p0), t.p0 - p) >= 0.0) return s;
  const TriangleLightSample ls = triangleLightSample(p, t.p0, t.p1, t.p2, u, float(WB_EMITTER_SOLID_ANGLE_RATIO));
  if (!(ls.pdf > 0.0)) return s;
  s.normal = ls.normal;
  s.position = ls.position;
  s.dist = ls.dist;
  s.wi = ls.wi;
  float cosLight = -dot(s.normal, s.wi);
  if (t.doubleSided != 0u) cosLight = abs(cosLight);
  if (!(cosLight > 0.0)) return s;
  const Material m = materials[t.materialIndex];
  vec3 le = m.emissive;
  if (m.emissiveTexture >= 0) {
    const vec3 b = emitterBarycentrics(s.position, t.p0, t.p1, t.p2);
    const vec2 uv = b.x * t.uv0 + b.y * t.uv1 + b.z * t.uv2;
    le *= sampleTexture(m.emissiveTexture, uv).rgb;
  }
  s.radiance = le;
  s.pdf = emitterAreaPdf(m.emissive) * ls.area * ls.pdf;
  return s;
#else
  s.normal = normalize(cross(t.p1 - t.p0, t.p2 - t.p0));
  vec3 b;
#if WB_EMITTER_SOLID_ANGLE == 1
  if (sphericalTriangleUseSolidAngle(p, t.p0, t.p1, t.p2)) {
    const float omega = sphericalTriangleSolidAngle(p, t.p0, t.p1, t.p2);
    if (!(omega > 0.0)) return s;
    s.wi = sampleSphericalTriangle(p, t.p0, t.p1, t.p2, u, omega);
    const vec3 hit = sphericalTriangleHit(p, s.wi, t.p0, t.p1, t.p2);
    if (!(hit.z > 0.0)) return s;
    b = vec3(1.0 - hit.x - hit.y, hit.x, hit.y);
    s.position = b.x * t.p0 + b.y * t.p1 + b.z * t.p2;
    s.dist = hit.z;
  } else
#endif
  {
    const float su = sqrt(u.x);
    b = vec3(1.0 - su, su * (1.0 - u.y), su * u.y);
    s.position = b.x * t.p0 + b.y * t.p1 + b.z * t.p2;
    const vec3 d = s.position - p;
    const float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) return s;
    s.dist = sqrt(dist2);
    s.wi = d / s.dist;
  }
  float cosLight = -dot(s.normal, s.wi);
  if (t.doubleSided != 0u) cosLight = abs(cosLight);
  if (!(cosLight > 0.0)) return s;  // the back of a single-sided emitter: black
  const Material m = materials[t.materialIndex];
  vec3 le = m.emissive;
  if (m.emissiveTexture >= 0) {
    const vec2 uv = b.x * t.uv0 + b.y * t.uv1 + b.z * t.uv2;
    le *= sampleTexture(m.emissiveTexture, uv).rgb;
  }
  s.radiance = le;
  s.pdf = emitterPdf(p, t.p0, t.p1, t.p2, m.emissive, s.dist, cosLight);
  return s;
#endif
}

#endif
