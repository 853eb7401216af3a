// Fetching what a ray hit: vertices through buffer device addresses, interpolated attributes, the material.
#ifndef WB_PT_HIT_DATA_GLSL
#define WB_PT_HIT_DATA_GLSL

struct HitVertexData {
  vec3 position;    // object space
  vec3 geoNormal;   // object space, from the triangle's winding (not normalised)
  vec3 normal;      // object space, interpolated (zero when the mesh had degenerate normals)
  vec4 tangent;
  vec2 uv;
  vec3 p0, p1, p2;  // object space vertex positions (emitters' MIS pdf)
};

GeometryInfo hitGeometry() { return geometries[gl_InstanceCustomIndexEXT + gl_GeometryIndexEXT]; }

HitVertexData fetchHit(GeometryInfo g, uint primitive, vec2 bary2) {
  IndexBuffer ib = IndexBuffer(uvec2(g.indexAddressLo, g.indexAddressHi));
  VertexBuffer vb = VertexBuffer(uvec2(g.vertexAddressLo, g.vertexAddressHi));
  const uint i0 = ib.i[3u * primitive + 0u];
  const uint i1 = ib.i[3u * primitive + 1u];
  const uint i2 = ib.i[3u * primitive + 2u];
  const Vertex v0 = vb.v[i0];
  const Vertex v1 = vb.v[i1];
  const Vertex v2 = vb.v[i2];
  const vec3 b = vec3(1.0 - bary2.x - bary2.y, bary2.x, bary2.y);
  HitVertexData h;
  h.position = b.x * v0.position + b.y * v1.position + b.z * v2.position;
  h.geoNormal = cross(v1.position - v0.position, v2.position - v0.position);
  h.normal = b.x * v0.normal + b.y * v1.normal + b.z * v2.normal;
  h.tangent = b.x * v0.tangent + b.y * v1.tangent + b.z * v2.tangent;
  h.uv = b.x * vec2(v0.u, v0.v) + b.y * vec2(v1.u, v1.v) + b.z * vec2(v2.u, v2.v);
  h.p0 = v0.position;
  h.p1 = v1.position;
  h.p2 = v2.position;
  return h;
}

// Base colour alpha (factor times texture), as alpha testing and blending see it.
float materialAlpha(Material m, vec2 uv) {
  float a = m.baseColorFactor.a;
  if (m.baseColorTexture >= 0) a *= sampleTexture(m.baseColorTexture, uv).a;
  return a;
}

// A hash of pixel, sample, primitive and geometry for stochastic transparency (PCG-style mixing).
uint hashCombine(uint h, uint v) {
  h ^= v + 0x9e3779b9u + (h << 6) + (h >> 2);
  h = h * 747796405u + 2891336453u;
  return ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
}
float alphaHash(uint primitive, uint geometry) {
  uvec2 pixel = gl_LaunchIDEXT.xy + pc.tileOffset;
  uint h = hashCombine(pixel.x, pixel.y);
  h = hashCombine(h, pc.sampleIndex ^ (pc.seed * 0x68bc21ebu));
  h = hashCombine(h, primitive);
  h = hashCombine(h, geometry);
  return float(h >> 8) * (1.0 / 16777216.0);
}

#endif
