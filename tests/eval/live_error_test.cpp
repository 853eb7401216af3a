// The live panel's running error: against a reference it is exactly eval's RMSE / relMSE; without one the
// half-snapshot estimate tracks the true noise MSE of a synthetic progressive render.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/live_error.h"
#include "eval/metrics.h"

using namespace wb::eval;

namespace {

// A progressive "renderer": per pixel the true value mu(x, y) (colour (1, 0.6, 0.3) x mu), estimated by the
// running mean of exponentially distributed samples (skewed, like path tracing).
struct Progressive {
  uint32_t w = 48, h = 32;
  std::mt19937_64 rng{7};
  std::vector<double> sum;
  uint32_t n = 0;
  Progressive() : sum(size_t(w) * h, 0.0) {}
  float mu(uint32_t x, uint32_t y) const { return 0.05f + 2.0f * float(x) / w * float(y + 3) / h; }
  ImageRGBA image(const std::vector<double>& values, double scale) const {
    ImageRGBA img;
    img.width = w;
    img.height = h;
    img.pixels.resize(size_t(w) * h * 4);
    for (size_t i = 0; i < values.size(); ++i) {
      const float v = float(values[i] * scale);
      img.pixels[4 * i] = v;
      img.pixels[4 * i + 1] = 0.6f * v;
      img.pixels[4 * i + 2] = 0.3f * v;
      img.pixels[4 * i + 3] = 1.0f;
    }
    return img;
  }
  ImageRGBA truth() const {
    std::vector<double> v(sum.size());
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) v[size_t(y) * w + x] = mu(x, y);
    return image(v, 1.0);
  }
  void addSample() {
    for (uint32_t y = 0; y < h; ++y) {
      for (uint32_t x = 0; x < w; ++x) {
        std::exponential_distribution<double> e(1.0 / mu(x, y));
        sum[size_t(y) * w + x] += e(rng);
      }
    }
    ++n;
  }
  ImageRGBA current() const { return image(sum, 1.0 / n); }
};

}  // namespace

TEST(LiveError, WithAReferenceItIsEvalsRmseAndRelMse) {
  Progressive p;
  LiveError e;
  const ImageRGBA ref = p.truth();
  e.setReference(ref, "truth");
  for (uint32_t s = 1; s <= 16; ++s) {
    p.addSample();
    if (e.wants(p.n, 0.0)) {
      const ImageRGBA img = p.current();
      e.add(img, p.n, 0.0);
      ASSERT_TRUE(e.latest());
      EXPECT_FALSE(e.latest()->estimated);
      EXPECT_DOUBLE_EQ(e.latest()->rmse, rmse(img, ref));
      EXPECT_DOUBLE_EQ(e.latest()->relMse, relMse(img, ref, 0.01));
    }
  }
  ASSERT_EQ(e.history().size(), 5u);                                   // 1, 2, 4, 8, 16
  EXPECT_LT(e.history().back().rmse, 0.5 * e.history().front().rmse);  // error falls as samples accumulate
}

TEST(LiveError, WithoutAReferenceTheHalfSnapshotEstimatesTheNoiseMse) {
  Progressive p;
  p.w = 160;
  p.h = 120;
  p.sum.assign(size_t(p.w) * p.h, 0.0);
  LiveError e;
  const ImageRGBA truth = p.truth();
  for (uint32_t s = 1; s <= 64; ++s) {
    p.addSample();
    if (e.wants(p.n, 0.0)) e.add(p.current(), p.n, 0.0);
  }
  ASSERT_EQ(e.history().size(), 6u);  // 2, 4, ..., 64 (1 has no half snapshot)
  EXPECT_EQ(e.history().front().samples, 2u);
  for (const auto& pt : e.history()) EXPECT_TRUE(pt.estimated);
  // The true MSE of the 64-sample image against the truth, and the estimate: agree within 10% (the bright
  // pixels dominate both; over 160x120 pixels each has a few percent of noise of its own).
  const double trueMse = mse(p.current(), truth);
  const double estimated = e.latest()->rmse * e.latest()->rmse;
  EXPECT_NEAR(estimated / trueMse, 1.0, 0.1) << "true " << trueMse << " estimated " << estimated;
}

TEST(LiveError, TheEstimateIsBlindToBiasTheReferenceIsNot) {
  Progressive p;
  LiveError withRef, estimate;
  const ImageRGBA biasedTruth = p.truth();
  withRef.setReference(biasedTruth, "truth");
  for (uint32_t s = 1; s <= 256; ++s) {
    p.addSample();
    // A renderer 2% too bright.
    const ImageRGBA img = p.image(p.sum, 1.02 / p.n);
    if (withRef.wants(p.n, 0.0)) withRef.add(img, p.n, 0.0);
    if (estimate.wants(p.n, 0.0)) estimate.add(img, p.n, 0.0);
  }
  // Against the reference the relMSE keeps at least the bias^2 (0.02^2); the noise estimate goes below it.
  EXPECT_GT(withRef.latest()->relMse, 0.02 * 0.02 * 0.9);
  EXPECT_LT(estimate.latest()->relMse, withRef.latest()->relMse);
}

TEST(LiveError, ReferenceSizes) {
  Progressive p;
  p.addSample();
  const ImageRGBA img = p.current();
  LiveError e;
  // Twice the size: box-downsampled.
  ImageRGBA big;
  big.width = img.width * 2;
  big.height = img.height * 2;
  big.pixels.resize(size_t(big.width) * big.height * 4, 0.25f);
  e.setReference(big, "big");
  e.add(img, 1, 0.0);
  ASSERT_TRUE(e.latest());
  EXPECT_TRUE(e.error().empty());
  // Another aspect ratio: no point, a reason naming both sizes.
  ImageRGBA odd = big;
  odd.width = 50;
  odd.height = 50;
  odd.pixels.resize(50 * 50 * 4);
  e.setReference(odd, "odd");
  e.add(img, 1, 0.0);
  EXPECT_FALSE(e.latest());
  EXPECT_NE(e.error().find("50x50"), std::string::npos) << e.error();
  EXPECT_NE(e.error().find("48x32"), std::string::npos) << e.error();
  // The size is checked when asked, before any point: the reason is there at once.
  e.setReference(odd, "odd");
  EXPECT_TRUE(e.error().empty());
  EXPECT_FALSE(e.checkSize(img.width, img.height));
  EXPECT_NE(e.error().find("50x50"), std::string::npos) << e.error();
  EXPECT_TRUE(e.checkSize(25, 25));
  EXPECT_FALSE(e.checkSize(0, 0));
  // A missing file.
  EXPECT_FALSE(e.loadReference("/nonexistent/ref.exr"));
  EXPECT_FALSE(e.error().empty());
}

TEST(LiveError, CheckpointsAndRestart) {
  LiveError e;
  EXPECT_FALSE(e.wants(0, 0.0));
  EXPECT_TRUE(e.wants(1, 0.0));
  EXPECT_TRUE(e.wants(8, 0.0));
  EXPECT_FALSE(e.wants(6, 0.0));  // no reference: powers of two only
  ImageRGBA ref;
  ref.width = ref.height = 4;
  ref.pixels.assign(64, 1.0f);
  e.setReference(ref, "r");
  e.add(ref, 1, 0.0);
  EXPECT_FALSE(e.wants(1, 10.0));  // already measured
  EXPECT_FALSE(e.wants(3, 1.0));
  EXPECT_TRUE(e.wants(3, 2.5));  // with a reference: also by time
  EXPECT_EQ(e.nextCheckpoint(3, 2.5), 4u);
  EXPECT_EQ(e.nextCheckpoint(5, 0.5), 8u);
  EXPECT_EQ(e.nextCheckpoint(5, 2.5), 6u);  // due by time
  e.restart();
  EXPECT_TRUE(e.history().empty());
}
