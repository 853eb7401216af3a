// Image error metrics and statistics for convergence studies and statistical render tests. Pure functions on
// ImageRGBA (RGB channels only; alpha is ignored). Sums are in float64.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "eval/image.h"

namespace wb::eval {

using Rgb = std::array<double, 3>;

// Throws std::invalid_argument unless a and b have the same size.
void requireSameSize(const ImageRGBA& a, const ImageRGBA& b, const char* what);

// Mean over pixels and RGB channels of (a - b)^2, and its square root.
double mse(const ImageRGBA& a, const ImageRGBA& b);
double rmse(const ImageRGBA& a, const ImageRGBA& b);
// Relative MSE: mean over pixels and RGB channels of (a - b)^2 / (b^2 + eps); b is the reference.
double relMse(const ImageRGBA& a, const ImageRGBA& reference, double eps = 0.01);
// Mean of each RGB channel over all pixels.
Rgb meanRgb(const ImageRGBA& image);
// Number of non-finite RGB values.
size_t countNonFinite(const ImageRGBA& image);

// Box downsample by an integer factor k (each output pixel is the mean of a k x k block). Throws
// std::invalid_argument unless k >= 1 divides both dimensions.
ImageRGBA boxDownsample(const ImageRGBA& image, uint32_t k);
// Box downsample to width x height; the size must divide the image's size by the same integer factor.
ImageRGBA downsampleTo(const ImageRGBA& image, uint32_t width, uint32_t height);

// Per-pixel statistics of independent runs (same size, different seeds): the mean image and the unbiased
// sample variance of one run's pixel value (divide by runs for the variance of the mean). Needs >= 2 runs.
struct RunStats {
  ImageRGBA mean;
  ImageRGBA variance;  // of a single run, per pixel and channel
  uint32_t runs = 0;
  // Mean over pixels and channels of the variance: the expected MSE of one run against its expectation.
  double meanVariance() const;
};
RunStats runStats(const std::vector<ImageRGBA>& runs);

// Firefly statistics on pixel luminance (Rec. 709 weights): max over mean and the fraction of pixels brighter
// than 10x the mean.
struct FireflyStats {
  double meanLuminance = 0;
  double maxLuminance = 0;
  double maxOverMean = 0;       // 0 when the mean is 0
  double fractionAbove10x = 0;  // pixels with luminance > 10 x mean, over all pixels
};
FireflyStats fireflyStats(const ImageRGBA& image);

// Absolute difference |a - b| averaged over RGB, mapped to a false-colour heat map (black, blue, magenta,
// yellow, white) with `scale` at full scale; scale <= 0 picks the 99th percentile of the difference.
// Returns RGBA8 ready for writePng8.
std::vector<uint8_t> errorHeatmap(const ImageRGBA& a, const ImageRGBA& b, double scale = 0,
                                  double* usedScale = nullptr);

// ---- Statistical comparison (in the spirit of Mitsuba's per-pixel Z-test) ----

// Distribution helpers (exposed for tests).
double normalCdf(double z);
double studentTCdf(double t, double dof);  // P(T <= t)
double regularizedIncompleteBeta(double a, double b, double x);

// A sample set: the per-pixel mean of independent runs and the variance of that mean (variance of one run
// divided by the number of runs), with the degrees of freedom of the variance estimate (runs - 1; a huge
// value for a reference whose variance is known or negligible).
struct MeanEstimate {
  ImageRGBA mean;
  ImageRGBA varianceOfMean;
  double dof = 0;
};
MeanEstimate estimateFromRuns(const std::vector<ImageRGBA>& runs);
// A reference with no variance information (e.g. a converged external render): zero variance.
MeanEstimate exactReference(const ImageRGBA& image);

struct StatTestOptions {
  double alpha = 1e-3;        // overall false-failure rate, split over the three tests (Bonferroni)
  double minStdError = 1e-6;  // floor on the per-pixel standard error (black pixels in both)
  // > 0: the test's variance of the mean is not taken from its own (few, noisy) runs but predicted from the
  // reference's as reference.varianceOfMean x this factor (= reference samples / test samples per pixel),
  // with the reference's degrees of freedom. Robust for heavy-tailed pixels when the reference has many more
  // runs.
  double testVarianceFromReference = 0;
};

struct StatTestResult {
  bool pass = true;
  // Per-pixel Welch t-tests with a Bonferroni correction over all pixels and channels.
  double minPValue = 1;
  double bonferroniThreshold = 0;
  uint32_t worstX = 0, worstY = 0;
  int worstChannel = 0;
  double worstTest = 0, worstReference = 0, worstStdError = 0;  // the values at the worst pixel
  bool pixelTestPass = true;
  // Chi-square-style: sum of t^2 over pixels against its expectation under the null (normal approximation).
  double chiSquareZ = 0;
  bool chiSquarePass = true;
  // Global: per-channel difference of image means with its standard error (Welch t over runs).
  Rgb meanDifference{0, 0, 0};  // relative: (test - reference) / reference
  Rgb meanT{0, 0, 0};
  double meanMinPValue = 1;
  bool meanTestPass = true;
  std::string summary() const;
};

// Tests H0: "test and reference have the same expected image". Fails on a pixel far outside its noise, on too
// much squared deviation overall, or on a per-channel mean bias beyond its noise.
StatTestResult statisticalTest(const MeanEstimate& test, const MeanEstimate& reference,
                               const StatTestOptions& options = {});

}  // namespace wb::eval
