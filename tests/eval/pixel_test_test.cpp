// The per-pixel significance test over runs (eval/pixel_test.h): an unbiased estimate is off the reference in
// about the test's level of pixels, a biased one in nearly all; the paired form sees a filter's shift that
// the runs' own noise would hide against the reference.
#include <gtest/gtest.h>

#include <random>

#include "eval/pixel_test.h"

using namespace wb::eval;

namespace {

ImageRGBA flat(uint32_t w, uint32_t h, float v) {
  ImageRGBA img;
  img.width = w;
  img.height = h;
  img.pixels.assign(size_t(w) * h * 4, v);
  return img;
}

// `runs` images of the reference plus Gaussian noise (sigma) plus `bias`.
std::vector<ImageRGBA> noisyRuns(const ImageRGBA& ref, int runs, float sigma, float bias, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> gauss(0.0f, sigma);
  std::vector<ImageRGBA> out;
  for (int k = 0; k < runs; ++k) {
    ImageRGBA img = ref;
    for (float& v : img.pixels) v += gauss(rng) + bias;
    out.push_back(std::move(img));
  }
  return out;
}

}  // namespace

TEST(PixelTest, StudentCriticalValues) {
  EXPECT_NEAR(studentTCritical(0.05, 1e6), 1.95996, 1e-3);  // the normal's
  EXPECT_NEAR(studentTCritical(0.05, 3), 3.18245, 1e-3);
  EXPECT_NEAR(studentTCritical(0.01, 7), 3.49948, 1e-3);
}

TEST(PixelTest, UnbiasedRunsAreOffInAboutAlphaOfThePixelsBiasedOnesInNearlyAll) {
  const ImageRGBA ref = flat(64, 64, 1.0f);
  const auto unbiased = noisyRuns(ref, 8, 0.1f, 0.0f, 1);
  const PixelTestResult u = pixelsOffReference(unbiased, ref, nullptr, 0.01);
  EXPECT_EQ(u.pixels, 64u * 64u);
  EXPECT_EQ(u.runs, 8u);
  EXPECT_LT(u.fraction(), 0.03) << "the false-positive rate is about 1%";
  const PixelTestResult b = pixelsOffReference(noisyRuns(ref, 8, 0.1f, 0.2f, 2), ref, nullptr, 0.01);
  EXPECT_GT(b.fraction(), 0.9);
  EXPECT_THROW(pixelsOffReference({ref}, ref), std::invalid_argument) << "one run has no variance";
}

TEST(PixelTest, ThePairedFormSeesAShiftSmallerThanTheNoise) {
  const ImageRGBA ref = flat(32, 32, 1.0f);
  const auto raw = noisyRuns(ref, 6, 0.2f, 0.0f, 3);
  std::vector<ImageRGBA> shifted = raw;
  for (auto& img : shifted)
    for (float& v : img.pixels) v -= 0.01f;  // 1/20 of the noise: invisible against the reference
  EXPECT_LT(pixelsOffReference(shifted, ref).fraction(), 0.05);
  EXPECT_GT(pixelsOffPaired(shifted, raw).fraction(), 0.99);
  EXPECT_EQ(pixelsOffPaired(raw, raw).significant, 0u) << "identical runs are off nowhere";
}
