// Image metrics and the variance-aware statistical test on images with known answers (CPU only).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/metrics.h"

using namespace wb::eval;

namespace {

ImageRGBA constant(uint32_t w, uint32_t h, float r, float g, float b) {
  ImageRGBA img;
  img.width = w;
  img.height = h;
  img.pixels.resize(size_t(w) * h * 4);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    img.pixels[4 * i] = r;
    img.pixels[4 * i + 1] = g;
    img.pixels[4 * i + 2] = b;
    img.pixels[4 * i + 3] = 1;
  }
  return img;
}

void set(ImageRGBA& img, uint32_t x, uint32_t y, float r, float g, float b) {
  float* p = &img.pixels[(size_t(y) * img.width + x) * 4];
  p[0] = r;
  p[1] = g;
  p[2] = b;
}

// A synthetic "renderer": the per-pixel true image mu (varying across the image, colour (1, 0.6, 0.3)),
// estimated by the mean of `spp` exponentially distributed samples (skewed like path tracing) per run.
struct Synthetic {
  uint32_t w = 32, h = 32;
  float mu(uint32_t x, uint32_t y) const { return 0.05f + 2.0f * float(x) / w * float(y + 3) / h; }
  ImageRGBA truth() const {
    ImageRGBA img = constant(w, h, 0, 0, 0);
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) set(img, x, y, mu(x, y), 0.6f * mu(x, y), 0.3f * mu(x, y));
    return img;
  }
  ImageRGBA run(std::mt19937_64& rng, int spp, float scale = 1.0f) const {
    ImageRGBA img = constant(w, h, 0, 0, 0);
    for (uint32_t y = 0; y < h; ++y) {
      for (uint32_t x = 0; x < w; ++x) {
        std::exponential_distribution<double> e(1.0 / mu(x, y));
        double s = 0;
        for (int i = 0; i < spp; ++i) s += e(rng);
        const float v = float(s / spp) * scale;
        set(img, x, y, v, 0.6f * v, 0.3f * v);
      }
    }
    return img;
  }
  std::vector<ImageRGBA> runs(std::mt19937_64& rng, int count, int spp, float scale = 1.0f) const {
    std::vector<ImageRGBA> out;
    for (int i = 0; i < count; ++i) out.push_back(run(rng, spp, scale));
    return out;
  }
};

}  // namespace

TEST(Metrics, MseRmseRelMseOnConstantImages) {
  const auto a = constant(4, 3, 1, 1, 1), b = constant(4, 3, 0.5f, 0.5f, 0.5f);
  EXPECT_DOUBLE_EQ(mse(a, b), 0.25);
  EXPECT_DOUBLE_EQ(rmse(a, b), 0.5);
  EXPECT_NEAR(relMse(a, b), 0.25 / (0.25 + 0.01), 1e-12);
  EXPECT_NEAR(relMse(a, b, 0.0), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(mse(a, a), 0.0);
}

TEST(Metrics, MseOnMixedPixels) {
  // Two pixels: differences (1, 0, 0) and (0, 2, 0): mse = (1 + 4) / 6. Reference values 0 and 1.
  auto a = constant(2, 1, 0, 0, 0), b = constant(2, 1, 0, 0, 0);
  set(a, 0, 0, 1, 0, 0);
  set(b, 1, 0, 1, 1, 1);
  set(a, 1, 0, 1, 3, 1);
  EXPECT_NEAR(mse(a, b), 5.0 / 6.0, 1e-12);
  // relMse: pixel 0 red: 1 / (0 + 0.01) = 100; pixel 1 green: 4 / (1 + 0.01).
  EXPECT_NEAR(relMse(a, b), (100.0 + 4.0 / 1.01) / 6.0, 1e-9);
  // Alpha is ignored.
  a.pixels[3] = 7;
  EXPECT_NEAR(mse(a, b), 5.0 / 6.0, 1e-12);
}

TEST(Metrics, SizeMismatchThrows) {
  EXPECT_THROW(mse(constant(2, 2, 0, 0, 0), constant(2, 3, 0, 0, 0)), std::invalid_argument);
}

TEST(Metrics, MeanPerChannel) {
  auto img = constant(2, 2, 1, 2, 3);
  set(img, 1, 1, 5, 2, -1);
  const Rgb m = meanRgb(img);
  EXPECT_DOUBLE_EQ(m[0], 2.0);
  EXPECT_DOUBLE_EQ(m[1], 2.0);
  EXPECT_DOUBLE_EQ(m[2], 2.0);
}

TEST(Metrics, BoxDownsample) {
  ImageRGBA img = constant(4, 4, 0, 0, 0);
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) set(img, x, y, float(y * 4 + x), 1, float(x));
  const auto d = boxDownsample(img, 2);
  ASSERT_EQ(d.width, 2u);
  ASSERT_EQ(d.height, 2u);
  EXPECT_FLOAT_EQ(d.at(0, 0, 0), (0 + 1 + 4 + 5) / 4.0f);
  EXPECT_FLOAT_EQ(d.at(1, 0, 0), (2 + 3 + 6 + 7) / 4.0f);
  EXPECT_FLOAT_EQ(d.at(0, 1, 0), (8 + 9 + 12 + 13) / 4.0f);
  EXPECT_FLOAT_EQ(d.at(1, 1, 2), 2.5f);
  EXPECT_FLOAT_EQ(d.at(1, 1, 1), 1.0f);
  // The mean is preserved.
  EXPECT_NEAR(meanRgb(d)[0], meanRgb(img)[0], 1e-6);
  const auto one = downsampleTo(img, 1, 1);
  EXPECT_FLOAT_EQ(one.at(0, 0, 0), 7.5f);
  EXPECT_THROW(boxDownsample(img, 3), std::invalid_argument);
  EXPECT_THROW(downsampleTo(img, 2, 1), std::invalid_argument);
  EXPECT_EQ(boxDownsample(img, 1).pixels, img.pixels);
}

TEST(Metrics, RunStatsMeanAndVariance) {
  const std::vector<ImageRGBA> runs = {constant(2, 2, 1, 0, 5), constant(2, 2, 2, 0, 5),
                                       constant(2, 2, 3, 0, 5)};
  const auto s = runStats(runs);
  EXPECT_EQ(s.runs, 3u);
  EXPECT_FLOAT_EQ(s.mean.at(1, 1, 0), 2.0f);
  EXPECT_FLOAT_EQ(s.variance.at(1, 1, 0), 1.0f);  // unbiased: ((1)^2 + 0 + 1) / 2
  EXPECT_FLOAT_EQ(s.variance.at(0, 0, 2), 0.0f);
  EXPECT_NEAR(s.meanVariance(), 1.0 / 3.0, 1e-7);
  EXPECT_THROW(runStats({constant(1, 1, 0, 0, 0)}), std::invalid_argument);
}

TEST(Metrics, FireflyStatistics) {
  auto img = constant(10, 10, 1, 1, 1);  // luminance 1
  set(img, 3, 4, 1000, 1000, 1000);
  const auto f = fireflyStats(img);
  EXPECT_NEAR(f.meanLuminance, (99.0 + 1000.0) / 100.0, 1e-9);
  EXPECT_NEAR(f.maxLuminance, 1000.0, 1e-9);
  EXPECT_NEAR(f.maxOverMean, 1000.0 / 10.99, 1e-6);
  EXPECT_DOUBLE_EQ(f.fractionAbove10x, 0.01);
  const auto flat = fireflyStats(constant(3, 3, 2, 2, 2));
  EXPECT_NEAR(flat.maxOverMean, 1.0, 1e-12);
  EXPECT_EQ(flat.fractionAbove10x, 0.0);
}

TEST(Metrics, ErrorHeatmap) {
  auto a = constant(2, 1, 0, 0, 0), b = constant(2, 1, 0, 0, 0);
  set(a, 1, 0, 3, 3, 3);
  double used = 0;
  const auto rgba = errorHeatmap(a, b, 3.0, &used);
  EXPECT_EQ(used, 3.0);
  ASSERT_EQ(rgba.size(), 8u);
  EXPECT_EQ(rgba[0], 0);    // no error: black
  EXPECT_EQ(rgba[4], 255);  // full scale: white
  EXPECT_EQ(rgba[5], 255);
  EXPECT_EQ(rgba[6], 255);
}

TEST(Distributions, KnownValues) {
  EXPECT_NEAR(normalCdf(1.959963985), 0.975, 1e-9);
  EXPECT_NEAR(normalCdf(0), 0.5, 1e-15);
  EXPECT_NEAR(studentTCdf(1.0, 1.0), 0.75, 1e-12);  // Cauchy
  EXPECT_NEAR(studentTCdf(2.131449546, 15.0), 0.975, 1e-8);
  EXPECT_NEAR(studentTCdf(-2.131449546, 15.0), 0.025, 1e-8);
  EXPECT_NEAR(studentTCdf(2.0, 2.0), 0.5 + 1.0 / std::sqrt(6.0), 1e-12);  // closed form for 2 dof
  EXPECT_NEAR(regularizedIncompleteBeta(2, 3, 0.4), 0.5248, 1e-12);
}

TEST(StatisticalTest, ExactMatchPasses) {
  Synthetic s;
  std::mt19937_64 rng(1);
  const auto r = statisticalTest(estimateFromRuns(s.runs(rng, 8, 4)), estimateFromRuns(s.runs(rng, 8, 4)));
  EXPECT_TRUE(r.pass) << r.summary();
}

// Unbiased noise passes (the false-failure rate stays near alpha); a 2% bias fails every time.
TEST(StatisticalTest, UnbiasedPassesAndTwoPercentBiasFails) {
  Synthetic s;
  int falseFailures = 0, detected = 0, detectedAgainstTruth = 0;
  const int trials = 40;
  for (int trial = 0; trial < trials; ++trial) {
    std::mt19937_64 rng(1000 + trial);
    // 16 runs of 64 samples: a 2% bias is ~8 standard errors of the image mean.
    const auto reference = estimateFromRuns(s.runs(rng, 16, 64));
    const auto unbiased = estimateFromRuns(s.runs(rng, 16, 64));
    const auto biased = estimateFromRuns(s.runs(rng, 16, 64, 1.02f));
    const auto ok = statisticalTest(unbiased, reference);
    falseFailures += ok.pass ? 0 : 1;
    if (!ok.pass) ADD_FAILURE() << "trial " << trial << ": " << ok.summary();
    const auto bad = statisticalTest(biased, reference);
    detected += bad.pass ? 0 : 1;
    EXPECT_FALSE(bad.meanTestPass) << bad.summary();
    EXPECT_NEAR(bad.meanDifference[0], 0.02, 0.01);
    // Against an exact reference (the truth itself).
    detectedAgainstTruth += statisticalTest(biased, exactReference(s.truth())).pass ? 0 : 1;
    EXPECT_TRUE(statisticalTest(unbiased, exactReference(s.truth())).pass);
  }
  EXPECT_EQ(falseFailures, 0);
  EXPECT_EQ(detected, trials);
  EXPECT_EQ(detectedAgainstTruth, trials);
}

// A local error (one pixel 3x too bright) fails the per-pixel test although the image mean barely moves.
TEST(StatisticalTest, LocalErrorFailsPixelTest) {
  Synthetic s;
  std::mt19937_64 rng(7);
  auto runs = s.runs(rng, 16, 64);
  for (auto& r : runs) {
    float* p = &r.pixels[(size_t(10) * r.width + 20) * 4];
    for (int c = 0; c < 3; ++c) p[c] *= 3.0f;
  }
  const auto r = statisticalTest(estimateFromRuns(runs), estimateFromRuns(s.runs(rng, 16, 64)));
  EXPECT_FALSE(r.pixelTestPass) << r.summary();
  EXPECT_EQ(r.worstX, 20u);
  EXPECT_EQ(r.worstY, 10u);
  EXPECT_FALSE(r.pass);
}

// Errors of both signs that cancel in the mean (a pattern) fail the chi-square-style test.
TEST(StatisticalTest, CancellingPatternFailsChiSquare) {
  Synthetic s;
  std::mt19937_64 rng(11);
  auto runs = s.runs(rng, 16, 16);
  for (auto& r : runs) {
    for (uint32_t y = 0; y < r.height; ++y)
      for (uint32_t x = 0; x < r.width; ++x) {
        const float f = ((x + y) % 2) ? 1.15f : 0.85f;
        for (int c = 0; c < 3; ++c) r.pixels[(size_t(y) * r.width + x) * 4 + c] *= f;
      }
  }
  const auto r = statisticalTest(estimateFromRuns(runs), estimateFromRuns(s.runs(rng, 16, 16)));
  EXPECT_FALSE(r.chiSquarePass) << r.summary();
  EXPECT_FALSE(r.pass);
}

TEST(StatisticalTest, DeterministicDifferenceFails) {
  const auto a = constant(4, 4, 1, 1, 1);
  auto b = a;
  set(b, 2, 2, 1.001f, 1, 1);
  EXPECT_FALSE(statisticalTest(exactReference(b), exactReference(a)).pass);
  EXPECT_TRUE(statisticalTest(exactReference(a), exactReference(a)).pass);
}
