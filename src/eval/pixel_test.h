// Per-pixel significance over independent runs: which pixels' means over the runs (seeds) are off a reference
// by more than their noise explains. The fraction of such pixels against the test's level says whether an
// estimator (or a filter of it) is biased where it counts; for an unbiased one it is the false-positive rate.
#pragma once
#include <cstdint>
#include <vector>

#include "eval/image.h"

namespace wb::eval {

struct PixelTestResult {
  uint32_t runs = 0;
  uint32_t pixels = 0;       // tested
  uint32_t significant = 0;  // pixels where some channel is significantly off
  double alpha = 0;          // each pixel's level (what an unbiased estimate gets, on average)
  double fraction() const { return pixels ? double(significant) / double(pixels) : 0.0; }
};

// Per pixel and RGB channel, a two-sided Student t test (runs - 1 degrees of freedom) of the mean of `runs`
// against `reference`, whose own variance per pixel and channel is `referenceVariance` (nullptr: exact); a
// pixel is significant when a channel's p-value is below alpha / 3. The standard error is floored at 1e-6 of
// the value (identical runs of an exact pixel). Needs at least 2 runs of the reference's size
// (std::invalid_argument otherwise).
PixelTestResult pixelsOffReference(const std::vector<ImageRGBA>& runs, const ImageRGBA& reference,
                                   const ImageRGBA* referenceVariance = nullptr, double alpha = 0.01);

// The paired form: a[i] and b[i] come from the same samples (a filter's output and its input), and the test
// is of the mean of a[i] - b[i] against 0: what the filter itself moves, without the reference's noise.
PixelTestResult pixelsOffPaired(const std::vector<ImageRGBA>& a, const std::vector<ImageRGBA>& b,
                                double alpha = 0.01);

// The two-sided critical value of Student's t: P(|T| > t) = p with `dof` degrees of freedom.
double studentTCritical(double p, double dof);

}  // namespace wb::eval
