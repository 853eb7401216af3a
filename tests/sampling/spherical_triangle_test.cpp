// Tests of shaders/shared/spherical_triangle.h: the solid angle, the uniformity of Arvo's sampling over it
// (so its pdf is 1 / solid angle, the value MIS uses), the hit point, and the choice between solid angle and
// area sampling.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <random>

#include "shared/spherical_triangle.h"
#include "stats.h"

namespace wb {
namespace {

using glm::dvec3;
using glm::vec2;
using glm::vec3;

// Solid angle by integrating cos(theta_light) / r^2 over the triangle's area (midpoint rule on n^2
// sub-triangles).
double solidAngleByArea(vec3 p, vec3 p0, vec3 p1, vec3 p2, int n) {
  const dvec3 a(p0), e1 = dvec3(p1) - a, e2 = dvec3(p2) - a, q(p);
  const dvec3 normal = glm::cross(e1, e2);
  const double area = 0.5 * glm::length(normal) / double(n) / double(n);
  const dvec3 unit = glm::normalize(normal);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      // The upright sub-triangle's centroid, and the inverted one's where there is one.
      for (int k = 0; k < (i + j < n - 1 ? 2 : 1); ++k) {
        const double u = k == 0 ? (i + 1.0 / 3.0) / n : (i + 2.0 / 3.0) / n;
        const double v = k == 0 ? (j + 1.0 / 3.0) / n : (j + 2.0 / 3.0) / n;
        const dvec3 d = a + u * e1 + v * e2 - q;
        const double r2 = glm::dot(d, d);
        sum += std::abs(glm::dot(unit, d)) / (r2 * std::sqrt(r2)) * area;
      }
    }
  }
  return sum;
}

struct Tri {
  vec3 p, p0, p1, p2;
};

// A spread of configurations: the Cornell light seen from the wall next to it, grazing, near, far, obtuse.
std::vector<Tri> triangles() {
  return {
      {vec3(0.0f), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)},  // one octant: pi / 2
      {vec3(-1.0f, 1.9f, 0.1f), vec3(-0.58f, 1.99f, -0.58f), vec3(0.58f, 1.99f, -0.58f),
       vec3(0.58f, 1.99f, 0.58f)},
      {vec3(-0.3f, 1.0f, 0.2f), vec3(-0.58f, 1.99f, -0.58f), vec3(0.58f, 1.99f, 0.58f),
       vec3(-0.58f, 1.99f, 0.58f)},
      {vec3(0.1f, 0.2f, 0.05f), vec3(-1, 0, -1), vec3(3, 0, -0.5f), vec3(0, 0, 2)},        // close: ~2 pi
      {vec3(0.0f, 0.0f, 10.0f), vec3(-1, -1, 0), vec3(1, -0.5f, 0), vec3(0, 1.5f, 0.2f)},  // far
      {vec3(0.2f, 0.3f, 0.4f), vec3(-2, 0, 0), vec3(2, 0, 0), vec3(0, 0.05f, 0.5f)},       // obtuse, sliver
  };
}

TEST(SphericalTriangle, SolidAngleMatchesTheAreaIntegral) {
  const auto octant = triangles()[0];
  EXPECT_NEAR(gpu::sphericalTriangleSolidAngle(octant.p, octant.p0, octant.p1, octant.p2),
              std::numbers::pi / 2, 1e-6);
  for (const Tri& t : triangles()) {
    const double omega = gpu::sphericalTriangleSolidAngle(t.p, t.p0, t.p1, t.p2);
    const double byArea = solidAngleByArea(t.p, t.p0, t.p1, t.p2, 400);
    std::printf("solid angle %.6f, by area integral %.6f\n", omega, byArea);
    EXPECT_NEAR(omega, byArea, 2e-3 * byArea + 1e-6);
    // Either winding, the same.
    EXPECT_NEAR(gpu::sphericalTriangleSolidAngle(t.p, t.p0, t.p2, t.p1), omega, 1e-5 * omega);
  }
  // In the triangle's plane: no solid angle, no NaN.
  EXPECT_EQ(gpu::sphericalTriangleSolidAngle(vec3(5, 0, 0), vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)), 0.0f);
  EXPECT_EQ(gpu::sphericalTriangleSolidAngle(vec3(0), vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)), 0.0f);
}

// Sampled directions land on the triangle, and in each of its 4^3 sub-triangles (midpoint subdivision) with
// the probability of that sub-triangle's solid angle over the whole: the density is uniform, 1 / solid angle.
// `sample` maps (triangle, u, omega) to a direction.
template <class Sampler>
void expectUniformOverTheSolidAngle(Sampler sample) {
  constexpr int kLevels = 3;
  for (const Tri& t : triangles()) {
    // Sub-triangles in barycentric space: 64 cells of the level-3 grid (upright and inverted).
    struct Cell {
      vec3 q0, q1, q2;
    };
    std::vector<Cell> cells = {{t.p0, t.p1, t.p2}};
    for (int level = 0; level < kLevels; ++level) {
      std::vector<Cell> next;
      for (const Cell& c : cells) {
        const vec3 m01 = 0.5f * (c.q0 + c.q1), m12 = 0.5f * (c.q1 + c.q2), m20 = 0.5f * (c.q2 + c.q0);
        next.push_back({c.q0, m01, m20});
        next.push_back({m01, c.q1, m12});
        next.push_back({m20, m12, c.q2});
        next.push_back({m01, m12, m20});
      }
      cells = next;
    }
    const double omega = gpu::sphericalTriangleSolidAngle(t.p, t.p0, t.p1, t.p2);
    const int n = 400000;
    std::vector<double> expected, observed(cells.size(), 0.0);
    for (const Cell& c : cells)
      expected.push_back(n * gpu::sphericalTriangleSolidAngle(t.p, c.q0, c.q1, c.q2) / omega);
    // Which cell a hit lies in: barycentrics with respect to each cell (the cells tile the triangle).
    const vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    int offTriangle = 0, nonFinite = 0;
    for (int i = 0; i < n; ++i) {
      const vec3 d = sample(t, vec2(uni(rng), uni(rng)), float(omega));
      if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) {
        ++nonFinite;
        continue;
      }
      const vec3 hit = gpu::sphericalTriangleHit(t.p, d, t.p0, t.p1, t.p2);
      const vec3 point = t.p0 + hit.x * e1 + hit.y * e2;
      // The clamped hit point must lie along the sampled direction (else it was off the triangle).
      const vec3 along = glm::normalize(point - t.p);
      if (!(hit.z > 0.0f) || glm::dot(along, d) < 1.0f - 1e-5f) ++offTriangle;
      // Cell by the 2D barycentric grid: level-3 cell (i, j) with upright/inverted half.
      const double u = hit.x * 8.0, v = hit.y * 8.0;
      int iu = std::min(int(u), 7), iv = std::min(int(v), 7);
      if (iu + iv > 7) iv = 7 - iu;
      const bool inverted = (u - iu) + (v - iv) > 1.0;
      // Map (iu, iv, inverted) to the subdivision's cell order by locating the cell containing the centroid.
      const vec3 centre = t.p0 + float((iu + (inverted ? 2.0 : 1.0) / 3.0) / 8.0) * e1 +
                          float((iv + (inverted ? 2.0 : 1.0) / 3.0) / 8.0) * e2;
      size_t best = 0;
      float bestDist = 1e30f;
      for (size_t c = 0; c < cells.size(); ++c) {
        const vec3 cc = (cells[c].q0 + cells[c].q1 + cells[c].q2) / 3.0f;
        const float dist = glm::dot(cc - centre, cc - centre);
        if (dist < bestDist) {
          bestDist = dist;
          best = c;
        }
      }
      observed[best] += 1.0;
    }
    EXPECT_EQ(nonFinite, 0);
    EXPECT_LE(offTriangle, n / 10000) << "directions that miss the triangle";
    const auto r = test::chiSquareTest(observed, expected);
    std::printf("omega %.4f: %s\n", omega, r.describe().c_str());
    EXPECT_GT(r.pValue, 1e-4) << r.describe();
  }
}

TEST(SphericalTriangle, SamplesAreUniformOverTheSolidAngle) {
  expectUniformOverTheSolidAngle([](const Tri& t, vec2 u, float omega) {
    return gpu::sampleSphericalTriangle(t.p, t.p0, t.p1, t.p2, u, omega);
  });
}

// The estimator Omega * f(d) of the integral of f over the triangle's directions agrees with area sampling's.
TEST(SphericalTriangle, EstimatesAgreeWithAreaSampling) {
  const Tri t = triangles()[1];  // the Cornell light from the top of the left wall
  auto f = [&](vec3 d) { return double(std::max(0.0f, d.x)) * (1.0 + d.z * d.z); };  // the wall's cosine, ...
  const double omega = gpu::sphericalTriangleSolidAngle(t.p, t.p0, t.p1, t.p2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const int n = 200000;
  double sumS = 0, sumS2 = 0, sumA = 0, sumA2 = 0;
  const vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
  const vec3 normal = glm::normalize(glm::cross(e1, e2));
  const double area = 0.5 * glm::length(glm::cross(e1, e2));
  for (int i = 0; i < n; ++i) {
    const double s = omega * f(gpu::sampleSphericalTriangle(t.p, t.p0, t.p1, t.p2, vec2(uni(rng), uni(rng)),
                                                            float(omega)));
    sumS += s;
    sumS2 += s * s;
    const float su = std::sqrt(uni(rng)), v = uni(rng);
    const vec3 point = t.p0 + su * (1.0f - v) * e1 + su * v * e2;
    const vec3 d = point - t.p;
    const double r2 = glm::dot(d, d);
    const double a = f(glm::normalize(d)) * std::abs(glm::dot(normal, glm::normalize(d))) / r2 * area;
    sumA += a;
    sumA2 += a * a;
  }
  const double meanS = sumS / n, meanA = sumA / n;
  const double varS = sumS2 / n - meanS * meanS, varA = sumA2 / n - meanA * meanA;
  const double sigma = std::sqrt(varS / n + varA / n);
  std::printf("solid angle %.5f (variance %.3g), area %.5f (variance %.3g): %.2f sigma\n", meanS, varS, meanA,
              varA, std::abs(meanS - meanA) / sigma);
  EXPECT_LT(std::abs(meanS - meanA), 4.0 * sigma);
  EXPECT_LT(varS, 0.5 * varA) << "next to the light, solid angle sampling should have far less variance";
}

TEST(SphericalTriangle, SolidAngleChosenNearLargeTrianglesOnly) {
  const vec3 p0(-0.58f, 1.99f, -0.58f), p1(0.58f, 1.99f, -0.58f), p2(0.58f, 1.99f, 0.58f);
  EXPECT_TRUE(gpu::sphericalTriangleUseSolidAngle(vec3(-1.0f, 1.9f, 0.0f), p0, p1, p2));  // wall next to it
  EXPECT_TRUE(gpu::sphericalTriangleUseSolidAngle(vec3(0.0f, 0.0f, 0.0f), p0, p1, p2));   // floor: 1.99 below
  // The longest edge (the diagonal, 1.64) against half the distance to the plane.
  EXPECT_TRUE(gpu::sphericalTriangleUseSolidAngle(vec3(0.0f, -1.2f, 0.0f), p0, p1, p2));   // 3.19 below
  EXPECT_FALSE(gpu::sphericalTriangleUseSolidAngle(vec3(0.0f, -1.4f, 0.0f), p0, p1, p2));  // 3.39 below
  EXPECT_FALSE(gpu::sphericalTriangleUseSolidAngle(vec3(0.0f, -5.0f, 0.0f), p0, p1, p2));
  // Degenerate triangle: never (no plane).
  EXPECT_FALSE(gpu::sphericalTriangleUseSolidAngle(vec3(0.0f), p0, p0, p1));
}

// ---- The streamlined technique (WB_EMITTER_SOLID_ANGLE=2): sphericalTriangleSetup/Sample, triangleLight*
// ----

TEST(SphericalTriangle, StreamlinedSamplerIsUniformOverTheSolidAngle) {
  expectUniformOverTheSolidAngle([](const Tri& t, vec2 u, float) {
    return gpu::sphericalTriangleSample(gpu::sphericalTriangleSetup(t.p, t.p0, t.p1, t.p2), u);
  });
}

// Both implement Arvo's mapping: the same u gives the same direction, and the same solid angle. Both lose
// float precision where u.x is near 0 (the sub-triangle (a, b, c') vanishes; a double-precision version of
// the mapping differs from either by up to ~5e-3 there), so the bound is on the rare large differences.
TEST(SphericalTriangle, StreamlinedSamplerMatchesTheFirst) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  for (const Tri& t : triangles()) {
    const gpu::SphericalTriangle st = gpu::sphericalTriangleSetup(t.p, t.p0, t.p1, t.p2);
    const float omega = gpu::sphericalTriangleSolidAngle(t.p, t.p0, t.p1, t.p2);
    EXPECT_NEAR(st.omega, omega, 1e-5f * omega);
    const int n = 20000;
    float worst = 0.0f;
    int far = 0;
    for (int i = 0; i < n; ++i) {
      const vec2 u(uni(rng), uni(rng));
      const vec3 d0 = gpu::sampleSphericalTriangle(t.p, t.p0, t.p1, t.p2, u, omega);
      const vec3 d1 = gpu::sphericalTriangleSample(st, u);
      EXPECT_NEAR(glm::length(d1), 1.0f, 1e-5f);
      const float difference = glm::length(d1 - d0);
      worst = std::max(worst, difference);
      far += difference > 1e-4f;
    }
    std::printf("omega %.5f: directions differ by up to %.2e, by more than 1e-4 in %d of %d\n", omega, worst,
                far, n);
    EXPECT_LT(worst, 2e-3f);
    EXPECT_LT(far, n / 500);
  }
  // A point on a vertex or in the plane: no solid angle, no NaN.
  EXPECT_EQ(gpu::sphericalTriangleSetup(vec3(0), vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)).omega, 0.0f);
  EXPECT_EQ(gpu::sphericalTriangleSetup(vec3(5, 0, 0), vec3(0), vec3(1, 0, 0), vec3(0, 1, 0)).omega, 0.0f);
}

// One triangle of the Cornell box's light (longest edge, the diagonal: 1.64) and points at growing distances
// below it, on the wall beside it and grazing: with ratio 1 the rule switches between the techniques along
// them.
const vec3 kLight0(-0.58f, 1.99f, -0.58f), kLight1(0.58f, 1.99f, 0.58f), kLight2(0.58f, 1.99f, -0.58f);
std::vector<vec3> switchPoints() {
  return {vec3(0.1f, 1.7f, 0.0f),   vec3(0.0f, 0.8f, 0.2f),  vec3(0.2f, 0.4f, -0.1f), vec3(0.0f, 0.3f, 0.0f),
          vec3(0.3f, 0.0f, 0.4f),   vec3(0.0f, -2.0f, 0.0f), vec3(-1.0f, 1.9f, 0.1f), vec3(-1.0f, 0.2f, 0.6f),
          vec3(-3.0f, 1.95f, 0.0f), vec3(0.9f, 1.0f, -0.9f)};
}

TEST(TriangleLight, RuleSwitchesWithTheRatio) {
  const vec3 n = glm::cross(kLight1 - kLight0, kLight2 - kLight0);
  const vec3 centroid = (kLight0 + kLight1 + kLight2) / 3.0f;
  int solid = 0, area = 0;
  for (const vec3& p : switchPoints()) {
    EXPECT_FALSE(gpu::triangleLightUseSolidAngle(p, kLight0, kLight1, kLight2, n, 0.0f));  // ratio 0: never
    EXPECT_TRUE(gpu::triangleLightUseSolidAngle(p, kLight0, kLight1, kLight2, n, 1e6f));   // 1e6: always
    (gpu::triangleLightUseSolidAngle(p, kLight0, kLight1, kLight2, n, 1.0f) ? solid : area)++;
  }
  // Ratio 1: the longest edge (the diagonal, 1.64) against the distance to the centroid.
  EXPECT_TRUE(
      gpu::triangleLightUseSolidAngle(centroid - vec3(0.0f, 1.6f, 0.0f), kLight0, kLight1, kLight2, n, 1.0f));
  EXPECT_FALSE(
      gpu::triangleLightUseSolidAngle(centroid - vec3(0.0f, 1.7f, 0.0f), kLight0, kLight1, kLight2, n, 1.0f));
  // Far points near the light's plane: area (the plane distance rule picked solid angle there).
  EXPECT_FALSE(gpu::triangleLightUseSolidAngle(vec3(-3.0f, 1.95f, 0.0f), kLight0, kLight1, kLight2, n, 1.0f));
  EXPECT_GE(solid, 4);
  EXPECT_GE(area, 4);
  // Degenerate triangle: never (no plane).
  EXPECT_FALSE(gpu::triangleLightUseSolidAngle(vec3(0.0f), kLight0, kLight0, kLight1, vec3(0.0f), 1.0f));
}

// The pdf triangleLightSample reports for its direction is the pdf triangleLightPdf gives for that direction
// from the light's point (distance and cosine as a ray that hits the light sees them): next-event estimation
// and the MIS weight of a BRDF sample that hits the light agree, with either technique. The point lies on the
// triangle.
TEST(TriangleLight, SamplePdfIsThePdfMisEvaluates) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  const vec3 e1 = kLight1 - kLight0, e2 = kLight2 - kLight0, n = glm::cross(e1, e2);
  const vec3 unit = glm::normalize(n);
  for (float ratio : {0.0f, 0.5f, 1.0f, 2.0f, 1e6f}) {
    double worstPdf = 0, worstOff = 0;
    int samples = 0;
    for (const vec3& p : switchPoints()) {
      for (int i = 0; i < 2000; ++i) {
        const gpu::TriangleLightSample s =
            gpu::triangleLightSample(p, kLight0, kLight1, kLight2, vec2(uni(rng), uni(rng)), ratio);
        if (!(s.pdf > 0.0f)) continue;
        ++samples;
        ASSERT_TRUE(std::isfinite(s.pdf) && std::isfinite(s.dist));
        EXPECT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
        EXPECT_NEAR(std::abs(glm::dot(s.normal, unit)), 1.0f, 1e-6f);
        // On the triangle: barycentrics within [0, 1] (up to rounding), along wi at dist.
        const vec3 d = s.position - kLight0;
        const float b1 = glm::dot(glm::cross(d, e2), n) / glm::dot(n, n);
        const float b2 = glm::dot(glm::cross(e1, d), n) / glm::dot(n, n);
        worstOff = std::max({worstOff, double(-b1), double(-b2), double(b1 + b2 - 1.0f)});
        EXPECT_LT(glm::length(p + s.dist * s.wi - s.position), 1e-4f);
        // The pdf as the hit on the light sees it.
        const vec3 toLight = s.position - p;
        const float dist = glm::length(toLight);
        const float cosLight = std::abs(glm::dot(unit, toLight / dist));
        const float pdf = gpu::triangleLightPdf(p, kLight0, kLight1, kLight2, dist, cosLight, ratio);
        worstPdf = std::max(worstPdf, std::abs(double(pdf) / double(s.pdf) - 1.0));
      }
    }
    std::printf(
        "ratio %g: %d samples, largest relative pdf difference %.2e, furthest off the triangle %.2e\n", ratio,
        samples, worstPdf, worstOff);
    EXPECT_GT(samples, 15000);
    EXPECT_LT(worstPdf, 1e-3);
    EXPECT_LT(worstOff, 1e-4);
  }
}

// The direct light a receiver gets from the triangle, integral of L cos(receiver) over its directions,
// estimated by f / pdf with the rule's technique (ratio 1: it switches along the points), with area sampling
// alone (ratio 0) and solid angle alone (ratio 1e6): all agree with a quadrature of the integral over the
// triangle's area.
TEST(TriangleLight, TechniquesAgreeInExpectationAcrossTheSwitch) {
  const vec3 receiver = glm::normalize(vec3(0.3f, 1.0f, -0.2f));
  auto f = [&](vec3 w) { return double(std::max(0.0f, glm::dot(receiver, w))); };
  const vec3 n = glm::cross(kLight1 - kLight0, kLight2 - kLight0);
  int switched = 0;
  for (const vec3& p : switchPoints()) {
    // Quadrature: midpoint rule on 400^2 sub-triangles of f(w) cos(light) / r^2 dA.
    const dvec3 a(kLight0), e1 = dvec3(kLight1) - a, e2 = dvec3(kLight2) - a, q(p);
    const dvec3 unit = glm::normalize(glm::cross(e1, e2));
    const int m = 400;
    const double dA = 0.5 * glm::length(glm::cross(e1, e2)) / m / m;
    double reference = 0.0;
    for (int i = 0; i < m; ++i) {
      for (int j = 0; i + j < m; ++j) {
        for (int k = 0; k < (i + j < m - 1 ? 2 : 1); ++k) {
          const double u = (i + (k == 0 ? 1.0 : 2.0) / 3.0) / m, v = (j + (k == 0 ? 1.0 : 2.0) / 3.0) / m;
          const dvec3 d = a + u * e1 + v * e2 - q;
          const double r2 = glm::dot(d, d), r = std::sqrt(r2);
          reference += f(vec3(d / r)) * std::abs(glm::dot(unit, d)) / (r2 * r) * dA;
        }
      }
    }
    switched += gpu::triangleLightUseSolidAngle(p, kLight0, kLight1, kLight2, n, 1.0f) ? 1 : 0;
    for (float ratio : {1.0f, 0.0f, 1e6f}) {
      std::mt19937 rng(17);
      std::uniform_real_distribution<float> uni(0.0f, 1.0f);
      const int count = 100000;
      double sum = 0, sum2 = 0;
      for (int i = 0; i < count; ++i) {
        const gpu::TriangleLightSample s =
            gpu::triangleLightSample(p, kLight0, kLight1, kLight2, vec2(uni(rng), uni(rng)), ratio);
        const double x = s.pdf > 0.0f ? f(s.wi) / s.pdf : 0.0;
        sum += x;
        sum2 += x * x;
      }
      const double mean = sum / count, sigma = std::sqrt(std::max(0.0, sum2 / count - mean * mean) / count);
      std::printf("p (%.1f, %.2f, %.1f), ratio %g: %.6f +- %.6f, quadrature %.6f (%.2f sigma)\n", p.x, p.y,
                  p.z, ratio, mean, sigma, reference, std::abs(mean - reference) / std::max(sigma, 1e-30));
      EXPECT_LT(std::abs(mean - reference), 4.0 * sigma + 2e-4 * reference);
    }
  }
  EXPECT_GT(switched, 0);
  EXPECT_LT(switched, int(switchPoints().size()));
}

}  // namespace
}  // namespace wb
