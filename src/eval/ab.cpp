#include "eval/ab.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "eval/metrics.h"

namespace wb::eval {
namespace {

// Two channel values are the same: equal, or both NaN (a NaN the edit did not touch).
bool sameValue(float a, float b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}

// |a - b| / max(|a|, |b|): 0 for equal values, infinity where one is not finite and the other differs.
double relativeDiff(float a, float b) {
  if (sameValue(a, b)) return 0;
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  const double d = std::fabs(double(a) - double(b));
  return d / std::max(std::fabs(double(a)), std::fabs(double(b)));
}

ImageRGBA meanOf(const std::vector<ImageRGBA>& runs) {
  ImageRGBA m = runs.front();
  if (runs.size() == 1) return m;
  const double inv = 1.0 / double(runs.size());
  for (size_t k = 0; k < m.pixels.size(); ++k) {
    double s = 0;
    for (const auto& r : runs) s += r.pixels[k];
    m.pixels[k] = float(s * inv);
  }
  return m;
}

bool bitwiseSame(const ImageRGBA& a, const ImageRGBA& b) {
  for (size_t i = 0; i < a.pixels.size(); i += 4)
    for (int c = 0; c < 3; ++c)
      if (!sameValue(a.pixels[i + c], b.pixels[i + c])) return false;
  return true;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

const char* imageVerdictName(ImageVerdict v) {
  switch (v) {
    case ImageVerdict::Identical:
      return "identical";
    case ImageVerdict::Rounding:
      return "rounding";
    case ImageVerdict::Changed:
      break;
  }
  return "changed";
}

const char* speedVerdictName(SpeedVerdict v) {
  switch (v) {
    case SpeedVerdict::Faster:
      return "faster";
    case SpeedVerdict::Slower:
      return "slower";
    case SpeedVerdict::WithinNoise:
      break;
  }
  return "within_noise";
}

std::vector<uint8_t> changedPixelMask(const ImageRGBA& a, const ImageRGBA& b) {
  requireSameSize(a, b, "changedPixelMask");
  std::vector<uint8_t> mask(size_t(a.width) * a.height, 0);
  for (size_t i = 0; i < mask.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (relativeDiff(a.pixels[4 * i + c], b.pixels[4 * i + c]) > kRoundingRelativeTolerance) mask[i] = 1;
  return mask;
}

ImageRGBA differenceImage(const ImageRGBA& oldImage, const ImageRGBA& newImage) {
  requireSameSize(oldImage, newImage, "differenceImage");
  ImageRGBA d = oldImage;
  for (size_t i = 0; i < d.pixels.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      const float a = oldImage.pixels[i + c], b = newImage.pixels[i + c];
      d.pixels[i + c] = sameValue(a, b) ? 0.0f : std::fabs(b - a);
    }
    d.pixels[i + 3] = 1;
  }
  return d;
}

ImageComparison compareImages(const std::vector<ImageRGBA>& oldRuns, const std::vector<ImageRGBA>& newRuns,
                              double alpha) {
  if (oldRuns.empty() || oldRuns.size() != newRuns.size())
    throw std::invalid_argument("compareImages: needs the same number (>= 1) of old and new runs");
  for (size_t k = 0; k < oldRuns.size(); ++k) {
    requireSameSize(oldRuns[k], oldRuns.front(), "compareImages");
    requireSameSize(newRuns[k], oldRuns.front(), "compareImages");
  }
  ImageComparison r;
  bool identical = true;
  for (size_t k = 0; k < oldRuns.size() && identical; ++k) identical = bitwiseSame(oldRuns[k], newRuns[k]);
  if (identical) return r;

  const ImageRGBA a = meanOf(oldRuns), b = meanOf(newRuns);
  const size_t n = size_t(a.width) * a.height;
  size_t changed = 0;
  for (size_t i = 0; i < n; ++i) {
    bool pixelChanged = false;
    for (int c = 0; c < 3; ++c) {
      const float x = a.pixels[4 * i + c], y = b.pixels[4 * i + c];
      const double rel = relativeDiff(x, y);
      r.maxRelDiff = std::max(r.maxRelDiff, rel);
      if (!sameValue(x, y)) {
        const double d = std::isfinite(x) && std::isfinite(y) ? std::fabs(double(y) - double(x))
                                                              : std::numeric_limits<double>::infinity();
        r.maxAbsDiff = std::max(r.maxAbsDiff, d);
      }
      if (rel > kRoundingRelativeTolerance) pixelChanged = true;
    }
    if (pixelChanged) ++changed;
  }
  r.changedPixelFraction = n ? double(changed) / double(n) : 0.0;
  r.rmse = rmse(b, a);
  r.relMse = relMse(b, a);
  // Differences of a few ulp that average away in the mean still differ run by run: the verdict also looks at
  // each run, so a change that cancels in the mean is not called rounding.
  double maxRunRel = r.maxRelDiff;
  for (size_t k = 0; k < oldRuns.size(); ++k)
    for (size_t i = 0; i < oldRuns[k].pixels.size(); i += 4)
      for (int c = 0; c < 3; ++c)
        maxRunRel = std::max(maxRunRel, relativeDiff(oldRuns[k].pixels[i + c], newRuns[k].pixels[i + c]));
  if (maxRunRel <= kRoundingRelativeTolerance) {
    r.verdict = ImageVerdict::Rounding;
    return r;
  }
  r.verdict = ImageVerdict::Changed;

  // Paired test: the runs share their seeds, so new - old per run is the estimate of the change, and its
  // spread over the runs is the noise of that estimate (far smaller than either image's own noise). The test
  // sees the new mean against the old mean held exact, with the paired differences' variance of the mean.
  MeanEstimate test;
  test.mean = b;
  test.varianceOfMean = a;
  const size_t runs = oldRuns.size();
  for (size_t k = 0; k < a.pixels.size(); ++k) {
    double mean = 0;
    for (size_t j = 0; j < runs; ++j) mean += double(newRuns[j].pixels[k]) - double(oldRuns[j].pixels[k]);
    mean /= double(runs);
    double var = 0;
    for (size_t j = 0; j < runs; ++j) {
      const double d = double(newRuns[j].pixels[k]) - double(oldRuns[j].pixels[k]) - mean;
      var += d * d;
    }
    var = runs > 1 ? var / double(runs - 1) / double(runs) : 0.0;
    test.varianceOfMean.pixels[k] = std::isfinite(var) ? float(var) : 0.0f;
  }
  test.dof = runs > 1 ? double(runs - 1) : 1e9;
  StatTestOptions options;
  options.alpha = alpha;
  const StatTestResult t = statisticalTest(test, exactReference(a), options);
  r.meanShiftSignificant = !(t.pixelTestPass && t.meanTestPass && t.chiSquarePass);
  r.meanShiftPValue = std::min(t.minPValue, t.meanMinPValue);
  return r;
}

SpeedComparison compareSpeed(const std::vector<double>& oldMs, const std::vector<double>& newMs,
                             double margin) {
  if (oldMs.empty() || oldMs.size() != newMs.size())
    throw std::invalid_argument("compareSpeed: needs the same number (>= 1) of old and new rounds");
  std::vector<double> ratios;
  for (size_t k = 0; k < oldMs.size(); ++k) ratios.push_back(newMs[k] > 0 ? oldMs[k] / newMs[k] : 1.0);
  SpeedComparison s;
  s.ratio = median(ratios);
  s.spread = {*std::min_element(ratios.begin(), ratios.end()),
              *std::max_element(ratios.begin(), ratios.end())};
  s.oldMsPerSample = median(oldMs);
  s.newMsPerSample = median(newMs);
  if (s.spread[0] > 1.0 + margin) {
    s.verdict = SpeedVerdict::Faster;
  } else if (s.spread[1] < 1.0 / (1.0 + margin)) {
    s.verdict = SpeedVerdict::Slower;
  }
  return s;
}

}  // namespace wb::eval
