// The A/B verdicts on images and timings with known answers (CPU only): identical, rounding, a change on
// known pixels with and without a mean shift, and the speed verdict from alternating rounds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/ab.h"

using namespace wb::eval;

namespace {

// `runs` noisy renders of a 16x16 image (exponential samples, like path tracing), seed k for run k.
std::vector<ImageRGBA> noisyRuns(size_t runs, uint32_t seedBase = 1) {
  std::vector<ImageRGBA> out;
  for (size_t k = 0; k < runs; ++k) {
    std::mt19937 rng(seedBase + uint32_t(k));
    std::exponential_distribution<float> e(1.0f);
    ImageRGBA img;
    img.width = img.height = 16;
    img.pixels.resize(16 * 16 * 4);
    for (size_t i = 0; i < 256; ++i) {
      const float mu = 0.2f + float(i % 16) / 16.0f;
      for (int c = 0; c < 3; ++c) img.pixels[4 * i + c] = mu * e(rng);
      img.pixels[4 * i + 3] = 1;
    }
    out.push_back(img);
  }
  return out;
}

}  // namespace

TEST(ABImage, SameRunsAreIdentical) {
  const auto runs = noisyRuns(4);
  const ImageComparison r = compareImages(runs, runs);
  EXPECT_EQ(r.verdict, ImageVerdict::Identical);
  EXPECT_EQ(r.rmse, 0.0);
  EXPECT_EQ(r.maxAbsDiff, 0.0);
  EXPECT_EQ(r.changedPixelFraction, 0.0);
  EXPECT_FALSE(r.meanShiftSignificant);
}

TEST(ABImage, NaNInBothIsIdentical) {
  auto runs = noisyRuns(2);
  runs[0].pixels[5] = std::nanf("");
  EXPECT_EQ(compareImages(runs, runs).verdict, ImageVerdict::Identical);
  auto other = runs;
  other[0].pixels[5] = 1.0f;
  const ImageComparison r = compareImages(runs, other);
  EXPECT_EQ(r.verdict, ImageVerdict::Changed);
  EXPECT_TRUE(std::isinf(r.maxAbsDiff));
}

TEST(ABImage, UlpDifferencesAreRounding) {
  const auto runs = noisyRuns(4);
  auto moved = runs;
  for (auto& img : moved)
    for (size_t i = 0; i < img.pixels.size(); i += 7) img.pixels[i] = std::nextafter(img.pixels[i], 10.0f);
  const ImageComparison r = compareImages(runs, moved);
  EXPECT_EQ(r.verdict, ImageVerdict::Rounding);
  EXPECT_GT(r.maxAbsDiff, 0.0);
  EXPECT_LE(r.maxRelDiff, kRoundingRelativeTolerance);
  EXPECT_EQ(r.changedPixelFraction, 0.0);
  EXPECT_FALSE(r.meanShiftSignificant);
}

TEST(ABImage, TwoPercentOnKnownPixelsIsASignificantChangeThere) {
  const auto runs = noisyRuns(4);
  auto scaled = runs;
  // The left half of the image (a material's pixels) scaled by 1.02, with the same samples.
  for (auto& img : scaled)
    for (uint32_t y = 0; y < 16; ++y)
      for (uint32_t x = 0; x < 8; ++x)
        for (int c = 0; c < 3; ++c) img.pixels[(size_t(y) * 16 + x) * 4 + c] *= 1.02f;
  const ImageComparison r = compareImages(runs, scaled);
  EXPECT_EQ(r.verdict, ImageVerdict::Changed);
  EXPECT_TRUE(r.meanShiftSignificant);
  EXPECT_DOUBLE_EQ(r.changedPixelFraction, 0.5);
  EXPECT_NEAR(r.maxRelDiff, 0.02 / 1.02, 1e-4);
  const auto mask = changedPixelMask(runs[0], scaled[0]);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) EXPECT_EQ(mask[y * 16 + x], x < 8 ? 1 : 0) << x << "," << y;
  const ImageRGBA d = differenceImage(runs[0], scaled[0]);
  EXPECT_GT(d.at(0, 0, 0), 0.0f);
  EXPECT_EQ(d.at(12, 3, 1), 0.0f);
}

TEST(ABImage, OtherNoiseWithTheSameMeanIsChangedWithoutMeanShift) {
  // Another sample sequence of the same expected image (e.g. a sampler edit that consumes numbers
  // differently): changed pixel for pixel, but the mean is where it was.
  const auto a = noisyRuns(16, 1), b = noisyRuns(16, 1000);
  const ImageComparison r = compareImages(a, b);
  EXPECT_EQ(r.verdict, ImageVerdict::Changed);
  EXPECT_FALSE(r.meanShiftSignificant) << r.meanShiftPValue;
  EXPECT_GT(r.rmse, 0.0);
  EXPECT_GT(r.relMse, 0.0);
}

TEST(ABImage, MismatchedInputsThrow) {
  EXPECT_THROW(compareImages({}, {}), std::invalid_argument);
  EXPECT_THROW(compareImages(noisyRuns(2), noisyRuns(3)), std::invalid_argument);
}

TEST(ABSpeed, EveryRoundBeyondTheMarginDecides) {
  const SpeedComparison slower = compareSpeed({10, 11, 10, 12, 10}, {20, 19, 25, 21, 20});
  EXPECT_EQ(slower.verdict, SpeedVerdict::Slower);
  EXPECT_LT(slower.ratio, 1.0);
  EXPECT_LE(slower.spread[0], slower.ratio);
  EXPECT_GE(slower.spread[1], slower.ratio);
  EXPECT_DOUBLE_EQ(slower.oldMsPerSample, 10.0);
  EXPECT_DOUBLE_EQ(slower.newMsPerSample, 20.0);

  const SpeedComparison faster = compareSpeed({20, 19, 25, 21, 20}, {10, 11, 10, 12, 10});
  EXPECT_EQ(faster.verdict, SpeedVerdict::Faster);
  EXPECT_GT(faster.ratio, 1.0);

  // One round the other way (a load spike): within noise.
  EXPECT_EQ(compareSpeed({10, 11, 30, 12, 10}, {20, 19, 12, 21, 20}).verdict, SpeedVerdict::WithinNoise);
  // Every round a little faster, but inside the margin: within noise.
  EXPECT_EQ(compareSpeed({10.2, 10.3, 10.1}, {10, 10, 10}).verdict, SpeedVerdict::WithinNoise);
  EXPECT_STREQ(speedVerdictName(SpeedVerdict::WithinNoise), "within_noise");
  EXPECT_THROW(compareSpeed({1}, {}), std::invalid_argument);
}
