#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer vertex stage: vertices pulled through buffer device addresses (GeometryInfo), one draw per primitive
// placement with the instance transform and geometry index in push constants.
#include "common.glsl"
#include "raster.glsl"

layout(location = VARYING_WORLD_POS) out vec3 outWorldPos;
layout(location = VARYING_NORMAL) out vec3 outNormal;
layout(location = VARYING_UV) out vec2 outUv;
layout(location = VARYING_MATERIAL) flat out uint outMaterial;

void main() {
  const GeometryInfo g = geometries[draw.geometryIndex];
  const Vertex v = fetchVertex(g, uint(gl_VertexIndex));
  const vec4 world = draw.model * vec4(v.position, 1.0);
  outWorldPos = world.xyz;
  outNormal = transpose(inverse(mat3(draw.model))) * v.normal;
  outUv = vec2(v.u, v.v);
  outMaterial = g.materialIndex;
  gl_Position = frame.viewProj * world;
}
