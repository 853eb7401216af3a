// Shading shared by the composite and the reflection rays: the path tracer's BRDF (shared/brdf.h) lit by the
// sun, plus a split of the ambient term into diffuse and specular parts.
#ifndef WB_HYBRID_LIGHTING_GLSL
#define WB_HYBRID_LIGHTING_GLSL
#include "../shared/brdf.h"

SurfaceMaterial hybridMaterial(vec3 baseColor, float metallic, float roughness, float specularFactor) {
  SurfaceMaterial m = makeSurfaceMaterial(baseColor, metallic, roughness);
  m.specularFactor = specularFactor;
  return m;
}

// Direct sunlight (times its visibility); wo and n point away from the surface.
vec3 sunDirect(SurfaceMaterial m, vec3 n, vec3 wo, float visibility) {
  if (frame.hasSun == 0u || visibility <= 0.0) return vec3(0.0);
  return brdfEval(m, n, wo, -frame.sunDirection) * frame.sunRadiance * visibility;
}

// Directional albedo of the specular lobe (Schlick Fresnel at the view angle) and of the diffuse lobe.
vec3 specularAlbedo(SurfaceMaterial m, vec3 n, vec3 wo) {
  const float c = max(dot(n, wo), 0.0);
  const vec3 dielectric = m.specularFactor * fresnelSchlick(dielectricF0(m), 1.0, c);
  const vec3 metal = fresnelSchlick(m.baseColor, 1.0, c);
  return mix(dielectric, metal, m.metallic);
}
vec3 diffuseAlbedo(SurfaceMaterial m, vec3 n, vec3 wo) {
  const float c = max(dot(n, wo), 0.0);
  const float fd = maxComponent(fresnelSchlick(dielectricF0(m), 1.0, c));
  return (1.0 - m.metallic) * (1.0 - m.specularFactor * fd) * m.baseColor;
}

#endif
