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
TEST(SphericalTriangle, SamplesAreUniformOverTheSolidAngle) {
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
      const vec3 d =
          gpu::sampleSphericalTriangle(t.p, t.p0, t.p1, t.p2, vec2(uni(rng), uni(rng)), float(omega));
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

}  // namespace
}  // namespace wb
