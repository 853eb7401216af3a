#include "eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace wb::eval {
namespace {

size_t pixelCount(const ImageRGBA& image) {
  return size_t(image.width) * image.height;
}

void requireValid(const ImageRGBA& image, const char* what) {
  if (image.pixels.size() != pixelCount(image) * 4) {
    throw std::invalid_argument(std::string(what) + ": image has " + std::to_string(image.pixels.size()) +
                                " floats for " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " RGBA");
  }
}

ImageRGBA blankLike(const ImageRGBA& image) {
  ImageRGBA out;
  out.width = image.width;
  out.height = image.height;
  out.pixels.assign(image.pixels.size(), 0.0f);
  return out;
}

// Two-sided p-value of a t statistic with `dof` degrees of freedom (normal beyond 1e6).
double twoSidedP(double t, double dof) {
  if (!std::isfinite(t)) return 0.0;
  if (dof > 1e6) return std::erfc(std::abs(t) / std::sqrt(2.0));
  return regularizedIncompleteBeta(0.5 * dof, 0.5, dof / (dof + t * t));
}

// Continued fraction for the incomplete beta function (modified Lentz).
double betaContinuedFraction(double a, double b, double x) {
  const double tiny = 1e-300;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= 500; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return h;
}

}  // namespace

void requireSameSize(const ImageRGBA& a, const ImageRGBA& b, const char* what) {
  requireValid(a, what);
  requireValid(b, what);
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument(std::string(what) + ": image sizes differ (" + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                                std::to_string(b.height) + ")");
  }
}

double mse(const ImageRGBA& a, const ImageRGBA& b) {
  requireSameSize(a, b, "mse");
  const size_t n = pixelCount(a);
  if (n == 0) return 0.0;
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels[4 * i + c]) - double(b.pixels[4 * i + c]);
      sum += d * d;
    }
  }
  return sum / double(3 * n);
}

double rmse(const ImageRGBA& a, const ImageRGBA& b) {
  return std::sqrt(mse(a, b));
}

double relMse(const ImageRGBA& a, const ImageRGBA& reference, double eps) {
  requireSameSize(a, reference, "relMse");
  const size_t n = pixelCount(a);
  if (n == 0) return 0.0;
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const double r = reference.pixels[4 * i + c];
      const double d = double(a.pixels[4 * i + c]) - r;
      sum += d * d / (r * r + eps);
    }
  }
  return sum / double(3 * n);
}

Rgb meanRgb(const ImageRGBA& image) {
  requireValid(image, "meanRgb");
  Rgb m{0, 0, 0};
  const size_t n = pixelCount(image);
  if (n == 0) return m;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) m[c] += image.pixels[4 * i + c];
  }
  for (double& v : m) v /= double(n);
  return m;
}

size_t countNonFinite(const ImageRGBA& image) {
  size_t count = 0;
  for (size_t i = 0; i < pixelCount(image); ++i) {
    for (int c = 0; c < 3; ++c) count += std::isfinite(image.pixels[4 * i + c]) ? 0 : 1;
  }
  return count;
}

ImageRGBA boxDownsample(const ImageRGBA& image, uint32_t k) {
  requireValid(image, "boxDownsample");
  if (k == 0 || image.width % k != 0 || image.height % k != 0) {
    throw std::invalid_argument("boxDownsample: factor " + std::to_string(k) + " does not divide " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  ImageRGBA out;
  out.width = image.width / k;
  out.height = image.height / k;
  out.pixels.assign(pixelCount(out) * 4, 0.0f);
  const double norm = 1.0 / double(k * k);
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = 0; x < out.width; ++x) {
      double sum[4] = {0, 0, 0, 0};
      for (uint32_t dy = 0; dy < k; ++dy) {
        for (uint32_t dx = 0; dx < k; ++dx) {
          const size_t src = (size_t(y * k + dy) * image.width + (x * k + dx)) * 4;
          for (int c = 0; c < 4; ++c) sum[c] += image.pixels[src + c];
        }
      }
      const size_t dst = (size_t(y) * out.width + x) * 4;
      for (int c = 0; c < 4; ++c) out.pixels[dst + c] = float(sum[c] * norm);
    }
  }
  return out;
}

ImageRGBA downsampleTo(const ImageRGBA& image, uint32_t width, uint32_t height) {
  if (width == 0 || height == 0 || image.width % width != 0 || image.height % height != 0 ||
      image.width / width != image.height / height) {
    throw std::invalid_argument("downsampleTo: cannot box-downsample " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " to " + std::to_string(width) + "x" +
                                std::to_string(height) + " (needs the same integer factor on both axes)");
  }
  return boxDownsample(image, image.width / width);
}

double RunStats::meanVariance() const {
  const size_t n = size_t(variance.width) * variance.height;
  if (n == 0) return 0.0;
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) sum += variance.pixels[4 * i + c];
  }
  return sum / double(3 * n);
}

RunStats runStats(const std::vector<ImageRGBA>& runs) {
  if (runs.size() < 2) throw std::invalid_argument("runStats: needs at least 2 runs");
  for (const auto& r : runs) requireSameSize(r, runs[0], "runStats");
  RunStats s;
  s.runs = uint32_t(runs.size());
  s.mean = blankLike(runs[0]);
  s.variance = blankLike(runs[0]);
  const size_t n = runs[0].pixels.size();
  const double count = double(runs.size());
  for (size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (const auto& r : runs) sum += r.pixels[i];
    const double mean = sum / count;
    double sq = 0;
    for (const auto& r : runs) {
      const double d = r.pixels[i] - mean;
      sq += d * d;
    }
    s.mean.pixels[i] = float(mean);
    s.variance.pixels[i] = float(sq / (count - 1.0));
  }
  return s;
}

FireflyStats fireflyStats(const ImageRGBA& image) {
  requireValid(image, "fireflyStats");
  FireflyStats f;
  const size_t n = pixelCount(image);
  if (n == 0) return f;
  std::vector<double> lum(n);
  double sum = 0;
  for (size_t i = 0; i < n; ++i) {
    const float* p = &image.pixels[4 * i];
    double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    if (!std::isfinite(l)) l = 0;
    lum[i] = l;
    sum += l;
    f.maxLuminance = std::max(f.maxLuminance, l);
  }
  f.meanLuminance = sum / double(n);
  if (f.meanLuminance > 0) {
    f.maxOverMean = f.maxLuminance / f.meanLuminance;
    size_t above = 0;
    for (double l : lum) above += l > 10.0 * f.meanLuminance ? 1 : 0;
    f.fractionAbove10x = double(above) / double(n);
  }
  return f;
}

std::vector<uint8_t> errorHeatmap(const ImageRGBA& a, const ImageRGBA& b, double scale, double* usedScale) {
  requireSameSize(a, b, "errorHeatmap");
  const size_t n = pixelCount(a);
  std::vector<double> diff(n);
  for (size_t i = 0; i < n; ++i) {
    double d = 0;
    for (int c = 0; c < 3; ++c) d += std::abs(double(a.pixels[4 * i + c]) - double(b.pixels[4 * i + c]));
    diff[i] = std::isfinite(d) ? d / 3.0 : std::numeric_limits<double>::max();
  }
  if (scale <= 0 && n > 0) {
    std::vector<double> sorted = diff;
    const size_t k = std::min(n - 1, size_t(0.99 * double(n)));
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(k), sorted.end());
    scale = sorted[k];
  }
  if (!(scale > 0)) scale = 1.0;
  if (usedScale) *usedScale = scale;
  // black -> blue -> magenta -> yellow -> white
  static const double stops[5][3] = {{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 0}, {1, 1, 1}};
  std::vector<uint8_t> out(n * 4);
  for (size_t i = 0; i < n; ++i) {
    const double t = std::clamp(diff[i] / scale, 0.0, 1.0) * 4.0;
    const int s = std::min(3, int(t));
    const double f = t - s;
    for (int c = 0; c < 3; ++c) {
      const double v = stops[s][c] * (1 - f) + stops[s + 1][c] * f;
      out[4 * i + c] = uint8_t(std::lround(v * 255.0));
    }
    out[4 * i + 3] = 255;
  }
  return out;
}

double normalCdf(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

double regularizedIncompleteBeta(double a, double b, double x) {
  if (x <= 0) return 0.0;
  if (x >= 1) return 1.0;
  const double lnFront =
      std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  const double front = std::exp(lnFront);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * betaContinuedFraction(a, b, x) / a;
  return 1.0 - front * betaContinuedFraction(b, a, 1.0 - x) / b;
}

double studentTCdf(double t, double dof) {
  if (dof > 1e6) return normalCdf(t);
  const double tail = 0.5 * regularizedIncompleteBeta(0.5 * dof, 0.5, dof / (dof + t * t));
  return t >= 0 ? 1.0 - tail : tail;
}

MeanEstimate estimateFromRuns(const std::vector<ImageRGBA>& runs) {
  const RunStats s = runStats(runs);
  MeanEstimate e;
  e.mean = s.mean;
  e.varianceOfMean = s.variance;
  const float inv = 1.0f / float(s.runs);
  for (float& v : e.varianceOfMean.pixels) v *= inv;
  e.dof = double(s.runs) - 1.0;
  return e;
}

MeanEstimate exactReference(const ImageRGBA& image) {
  MeanEstimate e;
  e.mean = image;
  e.varianceOfMean = blankLike(image);
  e.dof = 1e9;
  return e;
}

std::string StatTestResult::summary() const {
  char buf[640];
  std::snprintf(
      buf, sizeof buf,
      "%s: pixel test %s (min p %.3g vs Bonferroni %.3g at pixel %u,%u channel %d: %.6g vs %.6g, se %.3g); "
      "chi-square %s "
      "(z %.2f); mean test %s (relative mean difference %+.4f %+.4f %+.4f, t %.2f %.2f %.2f, min p "
      "%.3g)",
      pass ? "PASS" : "FAIL", pixelTestPass ? "pass" : "FAIL", minPValue, bonferroniThreshold, worstX, worstY,
      worstChannel, worstTest, worstReference, worstStdError, chiSquarePass ? "pass" : "FAIL", chiSquareZ,
      meanTestPass ? "pass" : "FAIL", meanDifference[0], meanDifference[1], meanDifference[2], meanT[0],
      meanT[1], meanT[2], meanMinPValue);
  return buf;
}

StatTestResult statisticalTest(const MeanEstimate& test, const MeanEstimate& reference,
                               const StatTestOptions& options) {
  requireSameSize(test.mean, reference.mean, "statisticalTest");
  requireSameSize(test.varianceOfMean, test.mean, "statisticalTest (test variance)");
  requireSameSize(reference.varianceOfMean, reference.mean, "statisticalTest (reference variance)");
  StatTestResult r;
  const double alphaEach = options.alpha / 3.0;
  const size_t n = pixelCount(test.mean);
  const double values = double(3 * n);
  r.bonferroniThreshold = alphaEach / values;

  const bool predicted = options.testVarianceFromReference > 0;
  const double testDof = predicted ? reference.dof : test.dof;
  // Per-pixel Welch t-tests; the sum of t^2 feeds the chi-square-style test.
  double sumT2 = 0, expectSum = 0, varSum = 0;
  bool chiUsable = true;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      const size_t k = 4 * i + c;
      const double d = double(test.mean.pixels[k]) - double(reference.mean.pixels[k]);
      const double vr = std::max(0.0, double(reference.varianceOfMean.pixels[k]));
      const double vt = predicted ? vr * options.testVarianceFromReference
                                  : std::max(0.0, double(test.varianceOfMean.pixels[k]));
      const double v = vt + vr;
      if (v <= 0 && d == 0) continue;  // deterministic and equal (e.g. black background in both)
      const double se = std::max(std::sqrt(v), options.minStdError);
      const double t = std::isfinite(d) ? d / se : std::numeric_limits<double>::infinity();
      // Welch-Satterthwaite degrees of freedom.
      double dof = 1e9;
      const double den = (vt > 0 ? vt * vt / testDof : 0.0) + (vr > 0 ? vr * vr / reference.dof : 0.0);
      if (den > 0) dof = std::min(1e9, v * v / den);
      const double p = twoSidedP(t, dof);
      if (p < r.minPValue) {
        r.minPValue = p;
        r.worstX = uint32_t(i % test.mean.width);
        r.worstY = uint32_t(i / test.mean.width);
        r.worstChannel = c;
        r.worstTest = test.mean.pixels[k];
        r.worstReference = reference.mean.pixels[k];
        r.worstStdError = se;
      }
      // t^2 ~ F(1, dof): mean dof/(dof-2), variance 2 dof^2 (dof-1) / ((dof-2)^2 (dof-4)).
      if (dof > 4.5) {
        sumT2 += std::isfinite(t) ? t * t : 1e300;
        expectSum += dof / (dof - 2.0);
        varSum += 2.0 * dof * dof * (dof - 1.0) / ((dof - 2.0) * (dof - 2.0) * (dof - 4.0));
      } else {
        chiUsable = false;
      }
    }
  }
  r.pixelTestPass = r.minPValue >= r.bonferroniThreshold;
  if (chiUsable && varSum > 0) {
    // The three channels of a pixel come from the same paths: assume them fully correlated (variance x 3).
    r.chiSquareZ = (sumT2 - expectSum) / std::sqrt(3.0 * varSum);
    r.chiSquarePass = 1.0 - normalCdf(r.chiSquareZ) >= alphaEach;
  }

  // Global per-channel mean test.
  const Rgb mt = meanRgb(test.mean), mr = meanRgb(reference.mean);
  // Pixels are independent estimates (separate sample streams), so the variance of an image mean is the sum
  // of the per-pixel variances over N^2; its estimate pools N x dof degrees of freedom.
  auto meanVariance = [&](const MeanEstimate& e, int c, double& dof, double scale) {
    double s = 0;
    for (size_t i = 0; i < n; ++i) s += e.varianceOfMean.pixels[4 * i + c];
    dof = std::min(1e9, e.dof * double(n));
    return n ? scale * s / (double(n) * double(n)) : 0.0;
  };
  double minP = 1;
  for (int c = 0; c < 3; ++c) {
    double dt = 0, dr = 0;
    const double vt = predicted ? meanVariance(reference, c, dt, options.testVarianceFromReference)
                                : meanVariance(test, c, dt, 1.0);
    const double vr = meanVariance(reference, c, dr, 1.0);
    const double d = mt[c] - mr[c];
    r.meanDifference[c] = mr[c] != 0 ? d / mr[c] : d;
    const double v = vt + vr;
    if (v <= 0) {
      r.meanT[c] = d == 0 ? 0 : std::numeric_limits<double>::infinity();
      minP = std::min(minP, d == 0 ? 1.0 : 0.0);
      continue;
    }
    const double den = (vt > 0 ? vt * vt / dt : 0.0) + (vr > 0 ? vr * vr / dr : 0.0);
    const double dof = den > 0 ? std::min(1e9, v * v / den) : 1e9;
    r.meanT[c] = d / std::sqrt(v);
    minP = std::min(minP, twoSidedP(r.meanT[c], dof));
  }
  r.meanMinPValue = minP;
  r.meanTestPass = minP * 3.0 >= alphaEach;  // Bonferroni over the three channels
  r.pass = r.pixelTestPass && r.chiSquarePass && r.meanTestPass;
  return r;
}

}  // namespace wb::eval
