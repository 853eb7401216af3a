// Area lights: sampling a point on the scene's emissive triangles (alias table over luminance * area) and the
// matching solid-angle pdf, also evaluated when a BRDF-sampled ray happens to hit an emitter (for MIS).
#ifndef WB_PT_EMITTERS_GLSL
#define WB_PT_EMITTERS_GLSL

layout(set = 0, binding = WB_BIND_EMITTERS, scalar) readonly buffer EmitterBlock { EmissiveTriangle emitters[]; };
layout(set = 0, binding = WB_BIND_EMITTER_ALIAS, scalar) readonly buffer EmitterAliasBlock {
  EnvAliasEntry emitterAlias[];
};

float emitterLuminance(vec3 emissiveFactor) { return luminance(emissiveFactor); }

// Area-measure pdf of a point on an emitter of this emissive factor (selection * 1 / area: the area cancels).
float emitterAreaPdf(vec3 emissiveFactor) {
  return frame.emitterTotalPower > 0.0 ? emitterLuminance(emissiveFactor) / frame.emitterTotalPower : 0.0;
}

struct EmitterSample {
  vec3 position;
  vec3 normal;   // geometric normal of the triangle (winding order)
  vec3 radiance; // emitted radiance towards the shading point (0 when it sees the back of a single-sided one)
  float pdf;     // solid-angle pdf at the shading point (0 = invalid)
  float dist;
  vec3 wi;
};

// u.x picks the entry, u.y the alias coin, (u.z, w) the point (uniform over the triangle).
EmitterSample sampleEmitter(vec3 p, float ux, float uy, float uz, float uw) {
  EmitterSample s;
  s.pdf = 0.0;
  s.radiance = vec3(0.0);
  const uint n = frame.emitterCount;
  uint i = min(uint(ux * float(n)), n - 1u);
  const EnvAliasEntry e = emitterAlias[i];
  if (uy >= e.prob) i = e.alias;
  const EmissiveTriangle t = emitters[i];
  const float su = sqrt(uz);
  const vec3 b = vec3(1.0 - su, su * (1.0 - uw), su * uw);
  s.position = b.x * t.p0 + b.y * t.p1 + b.z * t.p2;
  s.normal = normalize(cross(t.p1 - t.p0, t.p2 - t.p0));
  const vec3 d = s.position - p;
  const float dist2 = dot(d, d);
  if (!(dist2 > 0.0)) return s;
  s.dist = sqrt(dist2);
  s.wi = d / s.dist;
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
  s.pdf = emitterAreaPdf(m.emissive) * dist2 / cosLight;
  return s;
}

#endif
