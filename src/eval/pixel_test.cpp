#include "eval/pixel_test.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "eval/metrics.h"

namespace wb::eval {
namespace {

void requireRuns(const std::vector<ImageRGBA>& runs, const ImageRGBA& like, const char* what) {
  if (runs.size() < 2) throw std::invalid_argument(std::string(what) + ": at least 2 runs");
  for (const auto& r : runs) requireSameSize(r, like, what);
}

// Tests every pixel with `difference(run, i)` per run for value i (pixel * 4 + channel), against the
// reference's variance `refVariance(i)`; `magnitude(i)` scales the standard error's floor.
template <class Difference, class RefVariance, class Magnitude>
PixelTestResult test(size_t runs, uint32_t width, uint32_t height, double alpha, Difference difference,
                     RefVariance refVariance, Magnitude magnitude) {
  PixelTestResult r;
  r.runs = uint32_t(runs);
  r.alpha = alpha;
  const double critical = studentTCritical(alpha / 3.0, double(runs) - 1.0);
  const size_t pixels = size_t(width) * height;
  for (size_t p = 0; p < pixels; ++p) {
    bool significant = false;
    for (size_t c = 0; c < 3; ++c) {
      const size_t i = 4 * p + c;
      double sum = 0, sum2 = 0;
      for (size_t k = 0; k < runs; ++k) {
        const double d = difference(k, i);
        sum += d;
        sum2 += d * d;
      }
      const double mean = sum / double(runs);
      const double variance = std::max(0.0, (sum2 - sum * mean) / double(runs - 1));
      const double se = std::max(std::sqrt(variance / double(runs) + refVariance(i)),
                                 1e-6 * std::abs(magnitude(i)) + 1e-12);
      if (!std::isfinite(mean) || std::abs(mean) / se > critical) significant = true;
    }
    ++r.pixels;
    if (significant) ++r.significant;
  }
  return r;
}

}  // namespace

double studentTCritical(double p, double dof) {
  // P(|T| > t) = 2 (1 - cdf(t)) decreases in t: bisection.
  double lo = 0.0, hi = 1.0;
  while (2.0 * (1.0 - studentTCdf(hi, dof)) > p && hi < 1e6) hi *= 2.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (2.0 * (1.0 - studentTCdf(mid, dof)) > p ? lo : hi) = mid;
  }
  return hi;
}

PixelTestResult pixelsOffReference(const std::vector<ImageRGBA>& runs, const ImageRGBA& reference,
                                   const ImageRGBA* referenceVariance, double alpha) {
  requireRuns(runs, reference, "pixelsOffReference");
  if (referenceVariance) requireSameSize(*referenceVariance, reference, "pixelsOffReference (variance)");
  return test(
      runs.size(), reference.width, reference.height, alpha,
      [&](size_t k, size_t i) { return double(runs[k].pixels[i]) - double(reference.pixels[i]); },
      [&](size_t i) { return referenceVariance ? double(referenceVariance->pixels[i]) : 0.0; },
      [&](size_t i) { return reference.pixels[i]; });
}

PixelTestResult pixelsOffPaired(const std::vector<ImageRGBA>& a, const std::vector<ImageRGBA>& b,
                                double alpha) {
  if (a.size() != b.size()) throw std::invalid_argument("pixelsOffPaired: as many runs on both sides");
  requireRuns(a, a.front(), "pixelsOffPaired");
  requireRuns(b, a.front(), "pixelsOffPaired");
  return test(
      a.size(), a.front().width, a.front().height, alpha,
      [&](size_t k, size_t i) { return double(a[k].pixels[i]) - double(b[k].pixels[i]); },
      [](size_t) { return 0.0; }, [&](size_t i) { return b.front().pixels[i]; });
}

}  // namespace wb::eval
