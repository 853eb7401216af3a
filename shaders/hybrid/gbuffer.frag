#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer fragment stage: material with textures, alpha mask (discard below the cutoff), normals facing the
// camera. Outputs: albedo (rgb base colour, a metallic), normal (xyz, w roughness), emissive (rgb, a specular
// factor).
#include "common.glsl"
#include "raster.glsl"

layout(location = VARYING_WORLD_POS) in vec3 inWorldPos;
layout(location = VARYING_NORMAL) in vec3 inNormal;
layout(location = VARYING_UV) in vec2 inUv;
layout(location = VARYING_MATERIAL) flat in uint inMaterial;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outEmissive;

void main() {
  const Material m = materials[inMaterial];
  const HybridSurface s = evalSurface(m, inUv);
  if (alphaRejected(m, s.alpha)) discard;

  // Shade the side the camera sees. With the y-flipped projection and VK_FRONT_FACE_COUNTER_CLOCKWISE,
  // gl_FrontFacing is the winding's front, as the path tracer's geometric normal defines it.
  const vec3 toCamera = frame.cameraPosition - inWorldPos;
  vec3 n = inNormal;
  if (dot(n, n) > 1e-20) {
    n = normalize(n);
  } else {
    n = cross(dFdx(inWorldPos), dFdy(inWorldPos));
    n = dot(n, n) > 1e-30 ? normalize(n) : normalize(toCamera);
  }
  if (dot(n, toCamera) < 0.0) n = -n;
  if (any(isnan(n))) n = normalize(toCamera);

  // Emission from the front face only unless the material is double-sided.
  const vec3 emissive = gl_FrontFacing || (m.flags & WB_MATERIAL_DOUBLE_SIDED) != 0u ? s.emissive : vec3(0.0);
  outAlbedo = vec4(s.baseColor, s.metallic);
  outNormal = vec4(n, s.roughness);
  outEmissive = vec4(emissive, s.specularFactor);
}
