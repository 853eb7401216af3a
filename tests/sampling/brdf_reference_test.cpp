// The shaders' BRDF against an independent implementation of glTF 2.0 appendix B (with
// KHR_materials_specular) written here from the specification's formulas, in double precision: point by
// point, and the directional albedo of the shaders' *sampling* code (Monte Carlo of brdfSampleLocal's
// weights) against plain quadrature of the independent BRDF, at several roughness values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "shared/brdf.h"
#include "stats.h"

namespace wb {
namespace {

using glm::dvec3;
using glm::vec3;

struct RefMaterial {
  dvec3 baseColor;
  double metallic, roughness, specular;
  dvec3 specularColor{1.0};
};

// glTF 2.0 appendix B, section "Specular BRDF": D_GGX and the height-correlated Smith visibility
// V = G / (4 |N.L| |N.V|) with G = 2 |N.L| |N.V| / (|N.L| sqrt(a^2 + (1 - a^2) N.V^2) + |N.V| sqrt(...)).
double dGgx(double nh, double a) {
  if (nh <= 0.0) return 0.0;
  const double a2 = a * a, d = nh * nh * (a2 - 1.0) + 1.0;
  return a2 / (std::numbers::pi * d * d);
}
double vSmith(double nl, double nv, double hl, double hv, double a) {
  if (hl <= 0.0 || hv <= 0.0) return 0.0;
  const double a2 = a * a;
  return 0.5 / (std::abs(nl) * std::sqrt(a2 + (1.0 - a2) * nv * nv) +
                std::abs(nv) * std::sqrt(a2 + (1.0 - a2) * nl * nl));
}

// f(wo, wi) * cos(theta_i) for the appendix's metal_brdf / dielectric_brdf mix (fresnel_mix of
// KHR_materials_specular: f0 = min(0.04 specularColor, 1), F = f0 + (1 - f0)(1 - VdotH)^5, dielectric =
// (1 - specular * max(F)) * diffuse + specular * F * layer).
dvec3 reference(const RefMaterial& m, dvec3 v, dvec3 l) {
  if (v.z <= 0.0 || l.z <= 0.0) return dvec3(0.0);
  const dvec3 h = glm::normalize(v + l);
  const double a = std::max(m.roughness * m.roughness, 1e-4);  // alpha = roughness^2 (floored as the shader)
  const double vh = std::abs(glm::dot(v, h));
  const double layer = dGgx(h.z, a) * vSmith(l.z, v.z, glm::dot(h, l), glm::dot(h, v), a);
  const double schlick = std::pow(1.0 - vh, 5.0);
  const dvec3 diffuse = m.baseColor / std::numbers::pi;
  const dvec3 f0 = glm::min(0.04 * m.specularColor, dvec3(1.0));
  const dvec3 fd = f0 + (dvec3(1.0) - f0) * schlick;
  const double fdMax = std::max({fd.x, fd.y, fd.z});
  const dvec3 dielectric = (1.0 - m.specular * fdMax) * diffuse + m.specular * fd * layer;
  const dvec3 fm = m.baseColor + (dvec3(1.0) - m.baseColor) * schlick;
  const dvec3 metal = fm * layer;
  return ((1.0 - m.metallic) * dielectric + m.metallic * metal) * l.z;
}

gpu::SurfaceMaterial shaderMaterial(const RefMaterial& r) {
  gpu::SurfaceMaterial m = gpu::makeSurfaceMaterial(vec3(r.baseColor), float(r.metallic), float(r.roughness));
  m.specularFactor = float(r.specular);
  m.specularColor = vec3(r.specularColor);
  return m;
}

dvec3 dir(double thetaDeg, double phiDeg) {
  const double t = thetaDeg * std::numbers::pi / 180.0, p = phiDeg * std::numbers::pi / 180.0;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

std::vector<RefMaterial> materials() {
  std::vector<RefMaterial> out;
  for (double rough : {0.15, 0.3, 0.6, 1.0}) {
    out.push_back({dvec3(0.95, 0.64, 0.54), 1.0, rough, 1.0});                // copper-like metal
    out.push_back({dvec3(0.8, 0.4, 0.1), 0.0, rough, 1.0});                   // standard 4% dielectric
    out.push_back({dvec3(0.3, 0.6, 0.9), 0.0, rough, 0.5, {1.0, 0.5, 2.0}});  // KHR_materials_specular
    out.push_back({dvec3(0.6, 0.9, 0.3), 0.4, rough, 1.0});                   // partly metallic
  }
  return out;
}

TEST(BrdfReference, PointwiseMatchesAppendixB) {
  for (const auto& r : materials()) {
    const auto m = shaderMaterial(r);
    for (double tv : {0.0, 30.0, 60.0, 85.0}) {
      for (double tl : {5.0, 25.0, 50.0, 80.0}) {
        for (double phi : {0.0, 90.0, 180.0, 240.0}) {
          const dvec3 v = dir(tv, 0.0), l = dir(tl, phi);
          const dvec3 want = reference(r, v, l);
          const vec3 got = gpu::brdfEvalLocal(m, vec3(v), vec3(l));
          for (int c = 0; c < 3; ++c) {
            ASSERT_NEAR(got[c], want[c], 1e-4 + 2e-4 * want[c])
                << "roughness " << r.roughness << " metallic " << r.metallic << " view " << tv << " light "
                << tl << "/" << phi << " channel " << c;
          }
        }
      }
    }
  }
}

// Quadrature of the independent BRDF over the hemisphere around the mirror direction (fine steps near it).
dvec3 referenceAlbedo(const RefMaterial& r, dvec3 v) {
  const dvec3 axis = glm::normalize(dvec3(-v.x, -v.y, v.z));
  vec3 t3, b3;
  gpu::buildOrthonormalBasis(vec3(axis), t3, b3);
  const dvec3 t(t3), b(b3);
  const int nt = 1536, nphi = 384;
  dvec3 sum(0.0);
  for (int i = 0; i < nt; ++i) {
    const double u = (i + 0.5) / nt, theta = std::numbers::pi * u * u;
    const double dtheta = 2.0 * std::numbers::pi * u / nt;
    dvec3 ring(0.0);
    for (int j = 0; j < nphi; ++j) {
      const double phi = (j + 0.5) / nphi * 2.0 * std::numbers::pi;
      const dvec3 l = glm::normalize(std::sin(theta) * std::cos(phi) * t +
                                     std::sin(theta) * std::sin(phi) * b + std::cos(theta) * axis);
      ring += reference(r, v, l);
    }
    sum += ring * std::sin(theta) * dtheta * (2.0 * std::numbers::pi / nphi);
  }
  return sum;
}

TEST(BrdfReference, SampledAlbedoMatchesIndependentQuadrature) {
  uint32_t seed = 4242;
  for (const auto& r : materials()) {
    const auto m = shaderMaterial(r);
    for (double tv : {0.0, 45.0, 80.0}) {
      const dvec3 v = dir(tv, 0.0);
      const dvec3 want = referenceAlbedo(r, v);
      test::Rng rng(seed++);
      const int n = 300000;
      dvec3 sum(0.0), sum2(0.0);
      for (int i = 0; i < n; ++i) {
        const dvec3 w(gpu::brdfSampleLocal(m, vec3(v), rng.next3()).weight);
        sum += w;
        sum2 += w * w;
      }
      const dvec3 mean = sum / double(n);
      const dvec3 se = glm::sqrt(glm::max(sum2 / double(n) - mean * mean, dvec3(0.0)) / double(n));
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(mean[c], want[c], 4.0 * se[c] + 2e-3 * std::max(1.0, want[c]))
            << "roughness " << r.roughness << " metallic " << r.metallic << " specular " << r.specular
            << " view " << tv << " channel " << c;
      }
    }
  }
}

}  // namespace
}  // namespace wb
