// A/B comparison of two renders of the same scene with the same seeds and sample sequence (old pipeline A,
// new pipeline B): did the image change, and is B faster? Pure functions on images and timings (no GPU), used
// by live::ABComparison after each shader edit.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "eval/image.h"

namespace wb::eval {

// Float32 rounding tolerance: the largest per-channel relative difference |a - b| / max(|a|, |b|) that still
// counts as rounding. A float32 operation rounds to 2^-24 (6e-8) relative; a path's radiance is the result of
// a few hundred dependent operations (up to eight bounces of BRDF, pdf, MIS weights, transcendental functions
// with a few ulp of error each), averaged over the samples, so reordered arithmetic or a fused multiply-add
// moves a pixel by up to about 1e-6 relative. 1e-5 leaves a factor of ten above that, and stays four orders
// of magnitude below the smallest edit a user makes on purpose (a 1% change is 1e-2).
constexpr double kRoundingRelativeTolerance = 1e-5;

enum class ImageVerdict { Identical, Rounding, Changed };
const char* imageVerdictName(ImageVerdict v);  // "identical" | "rounding" | "changed"

struct ImageComparison {
  ImageVerdict verdict = ImageVerdict::Identical;
  double rmse = 0;        // of new against old, over RGB
  double relMse = 0;      // relative MSE, old as the reference
  double maxAbsDiff = 0;  // largest |new - old| over pixels and RGB (infinity when a value is NaN/Inf in one)
  double maxRelDiff = 0;  // largest |new - old| / max(|new|, |old|)
  double changedPixelFraction = 0;    // pixels with a channel beyond the rounding tolerance, over all pixels
  bool meanShiftSignificant = false;  // only for Changed: the statistical test rejects "same expected image"
  double meanShiftPValue = 1;         // the test's smallest p-value (pixel and image-mean tests)
};

// Compares runs of the old and the new pipeline rendered pairwise with the same seeds: oldRuns[k] and
// newRuns[k] used seed k. The verdict and the differences come from the mean images; the mean-shift test is
// the statistical image test (metrics.h) on the paired differences, whose per-pixel variance is estimated
// from the runs (a deterministic difference has zero variance and is significant). Needs >= 1 run of equal
// sizes; with one run the test uses zero variance.
ImageComparison compareImages(const std::vector<ImageRGBA>& oldRuns, const std::vector<ImageRGBA>& newRuns,
                              double alpha = 1e-3);

// The per-pixel mask of changed pixels (a channel beyond the rounding tolerance), row-major, 1 = changed.
std::vector<uint8_t> changedPixelMask(const ImageRGBA& a, const ImageRGBA& b);
// |new - old| per channel (alpha 1): the difference image.
ImageRGBA differenceImage(const ImageRGBA& oldImage, const ImageRGBA& newImage);

enum class SpeedVerdict { Faster, Slower, WithinNoise };
const char* speedVerdictName(SpeedVerdict v);  // "faster" | "slower" | "within_noise"

// speed_ratio = old ms per sample / new ms per sample: above 1 the new pipeline is faster.
struct SpeedComparison {
  double ratio = 1;                    // median of the per-round ratios
  std::array<double, 2> spread{1, 1};  // smallest and largest per-round ratio
  SpeedVerdict verdict = SpeedVerdict::WithinNoise;
  double oldMsPerSample = 0, newMsPerSample = 0;  // medians over rounds
};

// Relative margin around 1 that every round must clear for a faster/slower verdict.
constexpr double kSpeedMargin = 0.05;

// Per-round ms per sample of the old and the new pipeline, measured alternately (round k's two measurements
// back to back). Faster when every round's ratio is above 1 + margin, slower when every one is below
// 1 / (1 + margin), within noise otherwise. Needs equal, non-empty lists.
SpeedComparison compareSpeed(const std::vector<double>& oldMsPerSample,
                             const std::vector<double>& newMsPerSample, double margin = kSpeedMargin);

}  // namespace wb::eval
