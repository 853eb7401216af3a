// Tests of shaders/shared/sampling_math.h and brdf.h, the very code the shaders run.
#include <gtest/gtest.h>

#include <cstdio>

#include "shared/brdf.h"
#include "stats.h"

namespace wb {
namespace {

using glm::vec2;
using glm::vec3;
using gpu::SurfaceMaterial;
using test::Rng;
using test::SphereGrid;

constexpr int kSamples = 1000000;
constexpr double kMinP = 0.01;

vec3 viewDir(float thetaDeg) {
  float t = glm::radians(thetaDeg);
  return vec3(std::sin(t), 0.0f, std::cos(t));
}

SurfaceMaterial material(vec3 base, float metallic, float roughness, float specular = 1.0f) {
  SurfaceMaterial m = gpu::makeSurfaceMaterial(base, metallic, roughness);
  m.specularFactor = specular;
  return m;
}

TEST(SamplingChiSquare, CosineHemisphere) {
  SphereGrid grid{32, 64, 0.0};
  std::vector<double> obs(grid.size(), 0.0);
  Rng rng(1);
  for (int i = 0; i < kSamples; ++i) {
    vec3 d = gpu::sampleCosineHemisphere(rng.next2());
    ASSERT_GE(d.z, 0.0f);
    obs[grid.index(d)] += 1.0;
  }
  auto exp = grid.integrate([](const vec3& d) { return gpu::cosineHemispherePdf(d.z); }, 8, kSamples);
  auto r = test::chiSquareTest(obs, exp);
  std::printf("cosine: %s\n", r.describe().c_str());
  EXPECT_GT(r.pValue, kMinP) << r.describe();
}

TEST(SamplingChiSquare, GgxVisibleNormals) {
  const float roughness[] = {0.3f, 0.6f, 1.0f};
  const float views[] = {0.0f, 45.0f, 85.0f};
  int seed = 10;
  for (float rough : roughness) {
    for (float view : views) {
      float alpha = gpu::ggxAlpha(rough);
      vec3 wo = viewDir(view);
      SphereGrid grid{40, 80, 0.0};
      std::vector<double> obs(grid.size(), 0.0);
      Rng rng(seed++);
      for (int i = 0; i < kSamples; ++i) {
        vec3 h = gpu::sampleGgxVndf(wo, alpha, rng.next2());
        obs[grid.index(h)] += 1.0;
      }
      auto exp = grid.integrate([&](const vec3& h) { return gpu::ggxVndfPdf(wo, h, alpha); }, 12, kSamples);
      auto r = test::chiSquareTest(obs, exp);
      std::printf("vndf rough=%.2f view=%.0f: %s\n", rough, view, r.describe().c_str());
      EXPECT_GT(r.pValue, kMinP) << "roughness " << rough << " view " << view << ": " << r.describe();
    }
  }
}

struct BrdfCase {
  const char* name;
  SurfaceMaterial m;
};

std::vector<BrdfCase> brdfCases() {
  return {
      {"dielectric rough", material(vec3(0.8f, 0.5f, 0.3f), 0.0f, 0.8f)},
      {"dielectric smooth", material(vec3(0.2f, 0.6f, 0.9f), 0.0f, 0.3f)},
      {"dielectric coloured specular",
       [] {
         SurfaceMaterial m = material(vec3(0.5f), 0.0f, 0.5f, 0.7f);
         m.specularColor = vec3(20.0f, 10.0f, 1.0f);
         return m;
       }()},
      {"metal", material(vec3(0.95f, 0.64f, 0.54f), 1.0f, 0.4f)},
      {"metal rough", material(vec3(0.9f), 1.0f, 1.0f)},
      {"mixed", material(vec3(0.7f, 0.7f, 0.2f), 0.5f, 0.5f)},
  };
}

TEST(SamplingChiSquare, BrdfSampleMatchesBrdfPdf) {
  const float views[] = {10.0f, 60.0f, 88.0f};
  int seed = 100;
  for (const BrdfCase& c : brdfCases()) {
    for (float view : views) {
      vec3 wo = viewDir(view);
      SphereGrid grid{40, 96, 0.0};                   // upper hemisphere; valid samples never go below
      std::vector<double> obs(grid.size() + 1, 0.0);  // last bin: invalid samples
      Rng rng(seed++);
      for (int i = 0; i < kSamples; ++i) {
        gpu::BrdfSample s = gpu::brdfSampleLocal(c.m, wo, rng.next3());
        if (s.pdf > 0.0f) {
          ASSERT_GT(s.wi.z, 0.0f);
          obs[grid.index(s.wi)] += 1.0;
          // The sample's pdf is the combined pdf of its direction.
          ASSERT_NEAR(s.pdf, gpu::brdfPdfLocal(c.m, wo, s.wi), 1e-5f * s.pdf);
        } else {
          obs.back() += 1.0;
        }
      }
      auto exp = grid.integrate([&](const vec3& d) { return gpu::brdfPdfLocal(c.m, wo, d); }, 10, kSamples);
      double total = 0.0;
      for (double e : exp) total += e;
      exp.push_back(std::max(0.0, kSamples - total));
      auto r = test::chiSquareTest(obs, exp);
      std::printf("brdf %-28s view=%2.0f invalid=%.4f: %s\n", c.name, view, obs.back() / kSamples,
                  r.describe().c_str());
      EXPECT_GT(r.pValue, kMinP) << c.name << " view " << view << ": " << r.describe();
    }
  }
}

// Integral over the sphere of a direction function with a (theta, phi) grid about axis `r`, with theta = pi
// t^2 so directions near r (where GGX lobes are narrow) get fine steps. Plain quadrature: no importance
// sampling.
template <class F>
double sphereQuadrature(vec3 r, F f, int nt = 1024, int nphi = 256) {
  vec3 t, b;
  gpu::buildOrthonormalBasis(r, t, b);
  double sum = 0.0;
  for (int i = 0; i < nt; ++i) {
    double u = (i + 0.5) / nt;
    double theta = std::numbers::pi * u * u;
    double dtheta = 2.0 * std::numbers::pi * u / nt;
    double st = std::sin(theta), ct = std::cos(theta);
    double ring = 0.0;
    for (int j = 0; j < nphi; ++j) {
      double phi = (j + 0.5) / nphi * 2.0 * std::numbers::pi;
      vec3 local(static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                 static_cast<float>(ct));
      ring += f(glm::normalize(gpu::toWorld(local, t, b, r)));
    }
    sum += ring * st * dtheta * (2.0 * std::numbers::pi / nphi);
  }
  return sum;
}

TEST(SamplingPdf, IntegratesToOne) {
  // Cosine hemisphere and VNDF densities integrate to exactly one.
  double cosInt =
      sphereQuadrature(vec3(0, 0, 1), [](const vec3& d) { return gpu::cosineHemispherePdf(d.z); });
  EXPECT_NEAR(cosInt, 1.0, 1e-4);
  for (float rough : {0.1f, 0.3f, 0.6f, 1.0f}) {
    for (float view : {0.0f, 45.0f, 80.0f}) {
      float alpha = gpu::ggxAlpha(rough);
      vec3 wo = viewDir(view);
      double v = sphereQuadrature(
          vec3(0, 0, 1), [&](const vec3& h) { return gpu::ggxVndfPdf(wo, h, alpha); }, 2048, 256);
      EXPECT_NEAR(v, 1.0, 2e-3) << "vndf roughness " << rough << " view " << view;
      // The reflected-direction density integrates to one minus the probability of going below the horizon.
      vec3 r = vec3(-wo.x, -wo.y, wo.z);
      double refl = sphereQuadrature(r, [&](const vec3& wi) {
        if (wi.z <= 0.0f) return 0.0;
        return static_cast<double>(gpu::ggxReflectionPdf(wo, glm::normalize(wo + wi), alpha));
      });
      EXPECT_LE(refl, 1.0 + 2e-3);
      EXPECT_GT(refl, 0.3);
    }
  }
  // brdfPdf integrates to the fraction of valid samples of brdfSample.
  int seed = 7;
  for (const BrdfCase& c : brdfCases()) {
    for (float view : {0.0f, 70.0f}) {
      vec3 wo = viewDir(view);
      vec3 r = vec3(-wo.x, -wo.y, wo.z);
      double integral = sphereQuadrature(r, [&](const vec3& wi) { return gpu::brdfPdfLocal(c.m, wo, wi); });
      Rng rng(seed++);
      int valid = 0;
      const int n = 200000;
      for (int i = 0; i < n; ++i) valid += gpu::brdfSampleLocal(c.m, wo, rng.next3()).pdf > 0.0f ? 1 : 0;
      double frac = static_cast<double>(valid) / n;
      EXPECT_LE(integral, 1.0 + 2e-3) << c.name;
      EXPECT_NEAR(integral, frac, 4.0 * std::sqrt(frac * (1 - frac) / n) + 2e-3)
          << c.name << " view " << view;
    }
  }
}

// Directional albedo: Monte Carlo with the header's sampler (mean of f cos / pdf) vs plain quadrature of
// brdfEval.
void checkAlbedo(const SurfaceMaterial& m, float view, uint32_t seed, const char* what) {
  vec3 wo = viewDir(view);
  vec3 r = vec3(-wo.x, -wo.y, wo.z);
  glm::dvec3 quad(0.0);
  for (int ch = 0; ch < 3; ++ch) {
    quad[ch] = sphereQuadrature(
        r, [&](const vec3& wi) { return gpu::brdfEvalLocal(m, wo, wi)[ch]; }, 1024, 256);
  }
  Rng rng(seed);
  const int n = 400000;
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int i = 0; i < n; ++i) {
    gpu::BrdfSample s = gpu::brdfSampleLocal(m, wo, rng.next3());
    glm::dvec3 w(s.weight);
    sum += w;
    sum2 += w * w;
  }
  glm::dvec3 mean = sum / double(n);
  glm::dvec3 se = glm::sqrt(glm::max(sum2 / double(n) - mean * mean, glm::dvec3(0.0)) / double(n));
  std::printf("albedo %-22s rough=%.2f view=%2.0f: MC %.5f %.5f %.5f (se %.5f) quad %.5f %.5f %.5f\n", what,
              m.roughness, view, mean.x, mean.y, mean.z, se.y, quad.x, quad.y, quad.z);
  for (int ch = 0; ch < 3; ++ch) {
    EXPECT_NEAR(mean[ch], quad[ch], 4.0 * se[ch] + 2e-3 * std::max(1.0, quad[ch]))
        << what << " roughness " << m.roughness << " view " << view << " channel " << ch;
  }
}

TEST(SamplingAlbedo, MonteCarloMatchesQuadrature) {
  uint32_t seed = 1000;
  for (float rough : {0.1f, 0.3f, 0.6f, 1.0f}) {
    for (float view : {0.0f, 45.0f, 80.0f}) {
      checkAlbedo(material(vec3(1.0f), 1.0f, rough), view, seed++, "white metal");
      checkAlbedo(material(vec3(0.8f, 0.4f, 0.1f), 0.0f, rough), view, seed++, "dielectric");
    }
  }
  checkAlbedo(material(vec3(0.6f, 0.9f, 0.3f), 0.3f, 0.4f), 30.0f, seed++, "mixed");
}

TEST(SamplingAlbedo, WhiteFurnaceLambert) {
  SurfaceMaterial m = material(vec3(1.0f), 0.0f, 0.5f, 0.0f);
  for (float view : {0.0f, 30.0f, 60.0f, 85.0f, 89.9f}) {
    vec3 wo = viewDir(view);
    Rng rng(static_cast<uint32_t>(view * 10));
    const int n = 400000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += gpu::brdfSampleLocal(m, wo, rng.next3()).weight.y;
    double quad =
        sphereQuadrature(vec3(0, 0, 1), [&](const vec3& wi) { return gpu::brdfEvalLocal(m, wo, wi).y; });
    std::printf("white furnace view=%.1f: MC %.5f quad %.6f\n", view, sum / n, quad);
    EXPECT_NEAR(sum / n, 1.0, 5e-3) << "view " << view;
    EXPECT_NEAR(quad, 1.0, 1e-3) << "view " << view;
  }
}

TEST(SamplingRobustness, NoNanOrInf) {
  const float roughs[] = {0.0f, 1e-4f, 0.05f, 0.5f, 1.0f};
  const float metals[] = {0.0f, 0.5f, 1.0f};
  const float cosView[] = {1e-7f, 1e-4f, 0.01f, 0.5f, 1.0f};
  const float us[] = {0.0f, 1e-7f, 0.5f, 0.99999994f};
  Rng rng(5);
  int checked = 0;
  for (float rough : roughs) {
    for (float metal : metals) {
      for (float specular : {0.0f, 1.0f}) {
        SurfaceMaterial m = material(vec3(0.9f, 0.5f, 0.1f), metal, rough, specular);
        for (float cv : cosView) {
          vec3 wo(std::sqrt(1.0f - cv * cv), 0.0f, cv);
          std::vector<vec3> uList;
          for (float a : us)
            for (float b : us)
              for (float c : us) uList.emplace_back(a, b, c);
          for (int i = 0; i < 200; ++i) uList.push_back(rng.next3());
          for (const vec3& u : uList) {
            gpu::BrdfSample s = gpu::brdfSampleLocal(m, wo, u);
            ASSERT_TRUE(std::isfinite(s.pdf) && test::finite3(s.weight) && test::finite3(s.wi))
                << "rough " << rough << " metal " << metal << " cos " << cv;
            ASSERT_GE(s.pdf, 0.0f);
            if (s.pdf > 0.0f) {
              ASSERT_GT(s.wi.z, 0.0f);
            }
            vec3 wi = vec3(rng.next2() * 2.0f - 1.0f, 0.0f);
            wi.z = std::sqrt(std::max(0.0f, 1.0f - wi.x * wi.x - wi.y * wi.y));
            vec3 f = gpu::brdfEvalLocal(m, wo, wi);
            float p = gpu::brdfPdfLocal(m, wo, wi);
            ASSERT_TRUE(test::finite3(f) && std::isfinite(p));
            // Below the surface: zero.
            vec3 below(wi.x, wi.y, -wi.z - 1e-3f);
            ASSERT_EQ(gpu::brdfEvalLocal(m, wo, below), vec3(0.0f));
            ASSERT_EQ(gpu::brdfPdfLocal(m, wo, below), 0.0f);
            ++checked;
          }
        }
        // Grazing both ways, wo below, zero vectors.
        vec3 g(1.0f, 0.0f, 1e-7f);
        ASSERT_TRUE(test::finite3(gpu::brdfEvalLocal(m, g, g)));
        ASSERT_TRUE(std::isfinite(gpu::brdfPdfLocal(m, g, vec3(-1.0f, 0.0f, 1e-7f))));
        ASSERT_EQ(gpu::brdfSampleLocal(m, vec3(0.0f, 0.6f, -0.8f), vec3(0.5f)).pdf, 0.0f);
        vec3 z(0.0f);
        ASSERT_TRUE(test::finite3(gpu::brdfEval(m, z, z, z)));
        ASSERT_TRUE(std::isfinite(gpu::brdfPdf(m, z, z, z)));
        gpu::BrdfSample zs = gpu::brdfSample(m, z, z, vec3(0.5f));
        ASSERT_TRUE(test::finite3(zs.weight) && test::finite3(zs.wi) && std::isfinite(zs.pdf));
        ASSERT_TRUE(test::finite3(gpu::brdfEval(m, vec3(0, 0, 1), vec3(0, 0, 1), z)));
      }
    }
  }
  EXPECT_GT(checked, 10000);
  // Helpers on degenerate input.
  vec3 t, b;
  gpu::buildOrthonormalBasis(vec3(0.0f), t, b);
  EXPECT_TRUE(test::finite3(t) && test::finite3(b));
  gpu::buildOrthonormalBasis(vec3(0.0f, 0.0f, -1.0f), t, b);
  EXPECT_NEAR(glm::dot(glm::cross(t, b), vec3(0, 0, -1)), 1.0f, 1e-6f);
  EXPECT_TRUE(
      test::finite3(gpu::sampleGgxVndf(vec3(1.0f, 0.0f, 1e-7f), gpu::ggxAlpha(0.0f), vec2(0.99999994f))));
  EXPECT_EQ(gpu::powerHeuristic(1.0f, 0.0f, 1.0f, 0.0f), 0.0f);
  EXPECT_EQ(gpu::powerHeuristic(1.0f, 1e30f, 1.0f, 1e30f), 0.5f);
  EXPECT_NEAR(gpu::powerHeuristic(1.0f, 3.0f, 1.0f, 1.0f), 0.9f, 1e-6f);
  EXPECT_TRUE(std::isfinite(gpu::powerHeuristic(1.0f, INFINITY, 1.0f, 1.0f)));
}

TEST(SamplingRobustness, SmoothMetalIsAMirror) {
  // roughness 0 (alpha = 1e-4): samples concentrate on the mirror direction (GGX tails: P(tan theta_h > T) =
  // alpha^2 / (alpha^2 + T^2)) and carry weight ~ F; no NaN, no blow-up.
  SurfaceMaterial m = material(vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.0f);
  vec3 wo = glm::normalize(vec3(0.3f, 0.2f, 0.9f));
  vec3 mirror(-wo.x, -wo.y, wo.z);
  Rng rng(3);
  const int n = 100000;
  int far = 0;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < n; ++i) {
    gpu::BrdfSample s = gpu::brdfSampleLocal(m, wo, rng.next3());
    ASSERT_TRUE(test::finite3(s.weight) && std::isfinite(s.pdf));
    if (s.pdf > 0.0f) {
      ASSERT_EQ(s.lobe, WB_LOBE_SPECULAR);
      ASSERT_LE(s.weight.x, 1.0f);
    }
    far += glm::distance(s.wi, mirror) > 0.01f ? 1 : 0;
    sum += glm::dvec3(s.weight);
  }
  EXPECT_LT(far, n / 500);
  vec3 f = gpu::fresnelSchlick(m.baseColor, 1.0f, wo.z);
  EXPECT_NEAR(sum.x / n, f.x, 2e-3);
  EXPECT_NEAR(sum.z / n, f.z, 2e-3);
}

TEST(SamplingMaterial, LobeProbabilities) {
  vec3 wo = viewDir(40.0f);
  EXPECT_EQ(gpu::brdfDiffuseProbability(material(vec3(1.0f), 1.0f, 0.5f), wo.z), 0.0f);
  // specularFactor 0: no specular lobe, so every sample is diffuse.
  EXPECT_EQ(gpu::brdfDiffuseProbability(material(vec3(1.0f), 0.0f, 0.5f, 0.0f), wo.z), 1.0f);
  EXPECT_NEAR(gpu::brdfDiffuseProbability(material(vec3(1.0f), 0.0f, 0.5f, 1e-3f), wo.z), 0.99f, 1e-6f);
  float p = gpu::brdfDiffuseProbability(material(vec3(1.0f), 0.0f, 0.5f), 1.0f);
  EXPECT_NEAR(p, 0.96f, 1e-5f);  // F0 = 0.04 at normal incidence
  // A pure metal never produces a diffuse sample, even for u.x just below 1.
  SurfaceMaterial metal = material(vec3(0.5f), 1.0f, 0.5f);
  EXPECT_EQ(gpu::brdfSampleLocal(metal, wo, vec3(0.0f, 0.3f, 0.3f)).lobe, WB_LOBE_SPECULAR);
  // KHR_materials_specular: F0 = min(0.04 * specularColor, 1) * specularFactor at normal incidence.
  SurfaceMaterial spec = material(vec3(0.0f), 0.0f, 0.5f, 0.5f);
  spec.specularColor = vec3(50.0f, 10.0f, 1.0f);
  vec3 f0 = spec.specularFactor * gpu::fresnelSchlick(gpu::dielectricF0(spec), 1.0f, 1.0f);
  EXPECT_NEAR(f0.x, 0.5f, 1e-6f);
  EXPECT_NEAR(f0.y, 0.2f, 1e-6f);
  EXPECT_NEAR(f0.z, 0.02f, 1e-6f);
}

// offsetRay: the returned origin lies strictly on the normal's side of the surface the point was computed on,
// for triangles at scale 1e-3 .. 1e5, with hit points carrying float round-off.
TEST(SamplingOffsetRay, LeavesTheSurface) {
  Rng rng(11);
  for (double scale : {1e-3, 1.0, 1e3, 1e5}) {
    int bad = 0;
    for (int i = 0; i < 20000; ++i) {
      glm::dvec3 center = (glm::dvec3(rng.next3()) * 2.0 - 1.0) * scale;
      glm::dvec3 p0 = center + (glm::dvec3(rng.next3()) - 0.5) * scale;
      glm::dvec3 p1 = center + (glm::dvec3(rng.next3()) - 0.5) * scale;
      glm::dvec3 p2 = center + (glm::dvec3(rng.next3()) - 0.5) * scale;
      vec3 f0(p0), f1(p1), f2(p2);
      glm::dvec3 d0(f0), d1(f1), d2(f2);  // the float triangle, exactly, in double
      glm::dvec3 n = glm::cross(d1 - d0, d2 - d0);
      if (glm::length(n) < 1e-6 * scale * scale) continue;
      n = glm::normalize(n);
      if (rng.next() < 0.5f) n = -n;
      float b1 = rng.next(), b2 = rng.next();
      if (b1 + b2 > 1.0f) {
        b1 = 1.0f - b1;
        b2 = 1.0f - b2;
      }
      vec3 hit = f0 + b1 * (f1 - f0) + b2 * (f2 - f0);  // float hit point with round-off
      vec3 o = gpu::offsetRay(hit, vec3(n));
      double dist = glm::dot(glm::dvec3(o) - d0, n);
      if (!(dist > 0.0)) ++bad;
      // Still close to the surface: within a few thousand ulps of the coordinates.
      EXPECT_LT(glm::length(glm::dvec3(o) - glm::dvec3(hit)), 1e-3 * scale + 1e-4);
    }
    EXPECT_EQ(bad, 0) << "scale " << scale;
  }
  // Near the origin the offset is a fixed tiny step along n.
  vec3 o = gpu::offsetRay(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f));
  EXPECT_GT(o.y, 0.0f);
  EXPECT_EQ(o.x, 0.0f);
}

TEST(SamplingEquirect, RoundTripAndConvention) {
  EXPECT_NEAR(gpu::directionToEquirect(vec3(0, 0, -1), 0.0f).x, 0.5f, 1e-6f);
  EXPECT_NEAR(gpu::directionToEquirect(vec3(1, 0, 0), 0.0f).x, 0.75f, 1e-6f);
  EXPECT_NEAR(gpu::directionToEquirect(vec3(0, 1, 0), 0.0f).y, 0.0f, 1e-6f);
  EXPECT_NEAR(gpu::directionToEquirect(vec3(0, -1, 0), 0.0f).y, 1.0f, 1e-6f);
  Rng rng(2);
  for (int i = 0; i < 10000; ++i) {
    vec3 d = gpu::sampleUniformSphere(rng.next2());
    float rot = rng.next() * 6.0f - 3.0f;
    vec2 uv = gpu::directionToEquirect(d, rot);
    EXPECT_GE(uv.x, 0.0f);
    EXPECT_LE(uv.x, 1.0f);
    vec3 back = gpu::equirectToDirection(uv, rot);
    EXPECT_NEAR(glm::distance(back, d), 0.0f, 2e-5f);
  }
  // A positive rotation turns the map: the map's -Z column appears at rotateY(-Z, rot).
  vec3 moved = gpu::equirectToDirection(vec2(0.5f, 0.5f), 0.5f);
  EXPECT_NEAR(glm::distance(moved, gpu::rotateY(vec3(0, 0, -1), 0.5f)), 0.0f, 1e-6f);
}

}  // namespace
}  // namespace wb
