// The sun model shared by the path tracer and the hybrid modes (shaders/shared/sun.h), on the CPU: the disc's
// radiance integrates to the irradiance at normal incidence, cone samples are uniform inside the cone, the
// next-event estimate of the cone is the irradiance, and a ray sees the disc inside the cone only.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "shared/sun.h"
#include "stats.h"

using namespace wb::gpu;
using wb::test::Rng;

namespace {

// Integral over the cone of half-angle acos(cosMax) around `axis` of f(direction) dw, by the midpoint rule in
// (angle from the axis, azimuth), in double precision.
template <typename F>
double integrateCone(glm::dvec3 axis, double cosMax, F f, int steps = 800) {
  const double r = std::acos(cosMax);
  glm::vec3 tf, bf;
  buildOrthonormalBasis(glm::vec3(axis), tf, bf);
  const glm::dvec3 t(tf), b(bf);
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double a = (i + 0.5) * r / steps;
    for (int j = 0; j < steps; ++j) {
      const double phi = (j + 0.5) * 2.0 * std::numbers::pi / steps;
      const glm::dvec3 w = std::cos(a) * axis + std::sin(a) * (std::cos(phi) * t + std::sin(phi) * b);
      sum += f(w) * std::sin(a);
    }
  }
  return sum * (r / steps) * (2.0 * std::numbers::pi / steps);
}

}  // namespace

// sin^2 r = (1 - cos r)(1 + cos r) over the cone of L cos theta: L pi sin^2 r = E, from the real sun's size
// to a hemisphere.
TEST(Sun, DiscRadianceIntegratesToTheIrradianceAtNormalIncidence) {
  for (float diameterDeg : {0.53f, 2.0f, 20.0f, 90.0f, 178.0f}) {
    const float c = std::cos(glm::radians(diameterDeg * 0.5f));
    const vec3 e(2.0f, 1.0f, 0.5f);
    const vec3 l = sunDiscRadiance(e, c);
    const glm::dvec3 axis(0, 0, 1);
    const double projected = integrateCone(axis, c, [&](const glm::dvec3& w) { return w.z; });
    EXPECT_NEAR(l.x * projected, e.x, 1e-4 * e.x) << diameterDeg << " degrees";
    EXPECT_NEAR(l.z * projected, e.z, 1e-4 * e.z) << diameterDeg << " degrees";
    // The pdf is one over the cone's solid angle.
    EXPECT_NEAR(sunConePdf(c) * integrateCone(axis, c, [](const glm::dvec3&) { return 1.0; }), 1.0, 1e-4);
  }
}

// Directions of sampleCone lie inside the cone, with cos theta (to the axis) and the azimuth uniform: a
// chi-square test in the axis' frame.
TEST(Sun, ConeSamplesAreUniformInsideTheCone) {
  const vec3 axis = normalize(vec3(0.3f, -0.8f, 0.5f));
  const float c = std::cos(glm::radians(12.0f));
  vec3 t, b;
  buildOrthonormalBasis(axis, t, b);
  wb::test::SphereGrid grid;
  grid.zBins = 16;
  grid.phiBins = 16;
  grid.zMin = c;
  std::vector<double> observed(grid.size(), 0.0);
  Rng rng(7);
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const vec3 w = sampleCone(axis, c, rng.next2());
    ASSERT_NEAR(length(w), 1.0f, 1e-5f);
    ASSERT_GE(dot(w, axis), c - 1e-6f);
    observed[grid.index(toLocal(w, t, b, axis))] += 1.0;
  }
  const std::vector<double> expected(grid.size(), double(n) / grid.size());
  const auto r = wb::test::chiSquareTest(observed, expected);
  EXPECT_GT(r.pValue, 1e-4) << r.describe();
}

// Next-event estimation of a cone sun on a surface with normal n: E (n . sun) when the cone is above the
// surface, and the clipped integral when it crosses the horizon (samples below it count 0, as the path tracer
// skips them).
TEST(Sun, ConeSampleEstimatesTheIrradianceOfTheDisc) {
  const vec3 n(0.0f, 1.0f, 0.0f);
  const vec3 e(3.0f);
  struct Case {
    float elevationDeg, diameterDeg;
  };
  for (const Case cs : {Case{60.0f, 40.0f}, Case{10.0f, 40.0f}, Case{70.0f, 0.53f}}) {
    const float el = glm::radians(cs.elevationDeg);
    const vec3 toSun(std::cos(el), std::sin(el), 0.0f);
    const float c = std::cos(glm::radians(cs.diameterDeg * 0.5f));
    const vec3 l = sunDiscRadiance(e, c);
    const double exact = double(l.x) * integrateCone(glm::dvec3(toSun), c,
                                                     [&](const glm::dvec3& w) { return std::max(0.0, w.y); });
    Rng rng(11);
    const int count = 400000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < count; ++i) {
      const vec3 w = sampleCone(toSun, c, rng.next2());
      const double v = dot(w, n) > 0.0f ? double(l.x) * dot(w, n) / sunConePdf(c) : 0.0;
      sum += v;
      sum2 += v * v;
    }
    const double mean = sum / count;
    const double sigma = std::sqrt(std::max(0.0, sum2 / count - mean * mean) / count);
    EXPECT_NEAR(mean, exact, 4.0 * sigma + 1e-5 * exact) << cs.elevationDeg << " / " << cs.diameterDeg;
    if (cs.elevationDeg - cs.diameterDeg * 0.5f > 0.0f) {  // above the horizon: the delta sun's value
      EXPECT_NEAR(exact, e.x * std::sin(el), 1e-4 * e.x) << cs.elevationDeg;
    } else {  // crossing it: not the delta sun's value
      EXPECT_GT(std::abs(exact - e.x * std::sin(el)), 0.05 * exact);
    }
  }
}

TEST(Sun, RaysSeeTheDiscInsideTheConeOnly) {
  const vec3 sunDirection = normalize(vec3(0.2f, -1.0f, 0.1f));
  const vec3 e(1.5f);
  const float c = std::cos(glm::radians(5.0f));
  const vec3 l = sunDiscRadiance(e, c);
  EXPECT_EQ(sunRadianceAlong(-sunDirection, sunDirection, c, e), l);
  vec3 t, b;
  buildOrthonormalBasis(-sunDirection, t, b);
  const vec3 inside = normalize(-sunDirection + std::tan(glm::radians(4.9f)) * t);
  const vec3 outside = normalize(-sunDirection + std::tan(glm::radians(5.1f)) * t);
  EXPECT_EQ(sunRadianceAlong(inside, sunDirection, c, e), l);
  EXPECT_EQ(sunRadianceAlong(outside, sunDirection, c, e), vec3(0.0f));
  EXPECT_EQ(sunRadianceAlong(sunDirection, sunDirection, c, e), vec3(0.0f));  // looking away
  // A delta sun is never seen, not even straight on.
  EXPECT_TRUE(sunIsDelta(1.0f));
  EXPECT_FALSE(sunIsDelta(c));
  EXPECT_EQ(sunRadianceAlong(-sunDirection, sunDirection, 1.0f, e), vec3(0.0f));
}
