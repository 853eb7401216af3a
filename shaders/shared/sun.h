// The sun model of every renderer (GLSL and C++, see glsl_cpp.h). A directional light (DirectionalLight in
// scene_types.h) is a disc of angular radius r = acos(cosAngularRadius) around the direction towards it, or a delta
// light when cosAngularRadius is 1.
//  - DirectionalLight.radiance is the irradiance E the sun gives a surface facing it. The disc's radiance is
//    L = E / (pi sin^2 r): the cosine-weighted integral of L over a cone of half-angle r is pi sin^2 r, so a fully
//    visible sun gives a surface E cos(theta) whatever its size, and a sun keeps its power at normal incidence
//    when it gets a size.
//  - The path tracer samples the cone uniformly (pdf 1 / (2 pi (1 - cos r))) for next-event estimation and weighs
//    that sample by MIS against BRDF sampling; a BRDF-sampled ray that escapes inside the cone sees L with the
//    complementary weight (sunRadianceAlong in its miss shader). The hybrid modes trace their shadow rays to the
//    same cone samples.
#ifndef WB_SUN_H
#define WB_SUN_H
#include "sampling_math.h"

WB_NAMESPACE_BEGIN

WB_FN bool sunIsDelta(float cosAngularRadius) { return cosAngularRadius >= 1.0f; }

// A direction inside the cone of half-angle acos(cosMax) around the unit vector `axis`, uniform in solid angle
// (pdf sunConePdf(cosMax)).
WB_FN vec3 sampleCone(vec3 axis, float cosMax, vec2 u) {
  float cosTheta = 1.0f - u.x * (1.0f - cosMax);
  float sinTheta = sqrt(max(0.0f, 1.0f - cosTheta * cosTheta));
  float phi = 2.0f * kPi * u.y;
  vec3 t;
  vec3 b;
  buildOrthonormalBasis(axis, t, b);
  return normalize(cos(phi) * sinTheta * t + sin(phi) * sinTheta * b + cosTheta * axis);
}

// The solid-angle pdf of sampleCone: 1 / (2 pi (1 - cosMax)). 1 - cosMax is exact in float for cosMax in [0.5, 1].
WB_FN float sunConePdf(float cosMax) { return 1.0f / (kTwoPi * (1.0f - cosMax)); }

// The disc's radiance for irradiance E at normal incidence: E / (pi sin^2 r), sin^2 r = (1 - cos r)(1 + cos r).
WB_FN vec3 sunDiscRadiance(vec3 irradiance, float cosMax) {
  return irradiance * (1.0f / (kPi * (1.0f - cosMax) * (1.0f + cosMax)));
}

// What a ray travelling along `dir` sees of a sun travelling along `sunDirection`: the disc's radiance inside its
// cone, nothing elsewhere (nor ever for a delta sun).
WB_FN vec3 sunRadianceAlong(vec3 dir, vec3 sunDirection, float cosMax, vec3 irradiance) {
  if (sunIsDelta(cosMax) || dot(dir, -sunDirection) < cosMax) return vec3(0.0f);
  return sunDiscRadiance(irradiance, cosMax);
}

WB_NAMESPACE_END

#endif
