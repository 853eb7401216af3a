// Statistics helpers for the sampling tests: chi-square goodness of fit with a p-value from the regularized
// incomplete gamma function, and quadrature over (cos theta, phi) bins.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace wb::test {

// Regularized upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a) (series / continued fraction).
inline double regularizedGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1.0) {
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 100000; ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
      if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  const double fpmin = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / fpmin, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < fpmin) d = fpmin;
    c = b + an / c;
    if (std::fabs(c) < fpmin) c = fpmin;
    d = 1.0 / d;
    double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

struct ChiSquareResult {
  double chi2 = 0.0;
  int dof = 0;
  double pValue = 0.0;
  int pooledBins = 0;
  std::string describe() const {
    return "chi2=" + std::to_string(chi2) + " dof=" + std::to_string(dof) + " p=" + std::to_string(pValue) +
           " pooled=" + std::to_string(pooledBins);
  }
};

// Bins with expected count < minExpected are pooled into one bin (merged into the smallest regular bin if the
// pool itself stays below minExpected).
inline ChiSquareResult chiSquareTest(const std::vector<double>& observed, const std::vector<double>& expected,
                                     double minExpected = 5.0) {
  std::vector<std::pair<double, double>> bins;  // (expected, observed)
  double poolE = 0.0, poolO = 0.0;
  ChiSquareResult r;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < minExpected) {
      poolE += expected[i];
      poolO += observed[i];
      ++r.pooledBins;
    } else {
      bins.emplace_back(expected[i], observed[i]);
    }
  }
  if (poolE >= minExpected) {
    bins.emplace_back(poolE, poolO);
  } else if (!bins.empty() && (poolE > 0.0 || poolO > 0.0)) {
    auto it = std::min_element(bins.begin(), bins.end());
    it->first += poolE;
    it->second += poolO;
  }
  for (auto& [e, o] : bins) r.chi2 += (o - e) * (o - e) / e;
  r.dof = static_cast<int>(bins.size()) - 1;
  r.pValue = r.dof > 0 ? regularizedGammaQ(0.5 * r.dof, 0.5 * r.chi2) : 1.0;
  return r;
}

// Grid over the sphere (or upper hemisphere) in (z = cos theta, phi), z in [zMin, 1], phi in [0, 2 pi).
struct SphereGrid {
  int zBins = 48;
  int phiBins = 96;
  double zMin = -1.0;
  int index(const glm::vec3& d) const {
    double z = std::clamp(static_cast<double>(d.z), -1.0, 1.0);
    double phi = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x));
    if (phi < 0.0) phi += 2.0 * std::numbers::pi;
    int iz = static_cast<int>((z - zMin) / (1.0 - zMin) * zBins);
    int ip = static_cast<int>(phi / (2.0 * std::numbers::pi) * phiBins);
    iz = std::clamp(iz, 0, zBins - 1);
    ip = std::clamp(ip, 0, phiBins - 1);
    return iz * phiBins + ip;
  }
  int size() const { return zBins * phiBins; }
  // Integral of pdf over bin (iz, ip): midpoint rule with sub x sub cells, uniform in theta (not in z) so
  // lobes peaked at the pole get fine steps; exact solid angle per theta slice.
  double integrateBin(const std::function<double(const glm::vec3&)>& pdf, int iz, int ip, int sub) const {
    const double dphi = 2.0 * std::numbers::pi / phiBins / sub;
    double z0 = zMin + (1.0 - zMin) * iz / zBins, z1 = zMin + (1.0 - zMin) * (iz + 1) / zBins;
    double t0 = std::acos(std::clamp(z1, -1.0, 1.0)), t1 = std::acos(std::clamp(z0, -1.0, 1.0));
    double dt = (t1 - t0) / sub;
    double acc = 0.0;
    for (int a = 0; a < sub; ++a) {
      double theta = t0 + (a + 0.5) * dt;
      double s = std::sin(theta), z = std::cos(theta);
      double ring = 0.0;
      for (int b = 0; b < sub; ++b) {
        double phi = (ip * sub + b + 0.5) * dphi;
        glm::vec3 d(static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)),
                    static_cast<float>(z));
        ring += pdf(d);
      }
      acc += ring * (std::cos(t0 + a * dt) - std::cos(t0 + (a + 1) * dt));
    }
    return acc * dphi;
  }
  // Integral over every bin times scale. Adaptive: where the sub and sub/2 estimates disagree by more than
  // 2e-4 relative, the bin is re-integrated with 2x, then 4x finer cells.
  std::vector<double> integrate(const std::function<double(const glm::vec3&)>& pdf, int sub,
                                double scale) const {
    std::vector<double> out(size(), 0.0);
    for (int iz = 0; iz < zBins; ++iz) {
      for (int ip = 0; ip < phiBins; ++ip) {
        double fine = integrateBin(pdf, iz, ip, sub);
        double coarse = integrateBin(pdf, iz, ip, sub / 2);
        for (int k = 2; k <= 4 && std::fabs(fine - coarse) > 2e-4 * fine; k *= 2) {
          coarse = fine;
          fine = integrateBin(pdf, iz, ip, sub * k);
        }
        out[static_cast<size_t>(iz) * phiBins + ip] = fine * scale;
      }
    }
    return out;
  }
};

// Uniform float in [0,1) from 24 random bits.
struct Rng {
  std::mt19937 gen;
  explicit Rng(uint32_t seed) : gen(seed) {}
  float next() { return static_cast<float>(gen() >> 8) * (1.0f / 16777216.0f); }
  glm::vec2 next2() {
    float a = next();
    return {a, next()};
  }
  glm::vec3 next3() {
    float a = next();
    float b = next();
    return {a, b, next()};
  }
};

inline bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace wb::test
