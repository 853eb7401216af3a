// live::ABComparison judges the estimator, not the denoiser: with the session's denoiser on, the images it
// compares are the path tracer's raw means (those the live renderer gives for the same seeds), not denoised
// ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../render/gpu_fixture.h"
#include "live/ab_comparison.h"
#include "render/path_tracer.h"

using namespace wb;

TEST(ABComparison, ComparesTheRawImagesWhenTheDenoiserIsOn) {
  render::SessionOptions o;
  o.settings.width = o.settings.height = 16;
  o.settings.denoise = true;
  o.quiet = true;
  auto s = wb::testing::makeSession(o);
  render::PathTracer& live = s->pathTracer();
  render::Pass& pass = *live.passes().at(0);
  // Both sides are the installed pipeline: the comparison's images are its raw means over seeds 0..spp-1.
  live::HotReload::InstalledPass ip{&pass, &live, 0, pass.name(), pass.installed(), pass.installed()};
  live::ABComparison ab(*s, {16, 16, 3, 2});
  const auto outcomes = ab.compare({ip});
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].result.image.verdict, eval::ImageVerdict::Identical);

  // The same runs on the live renderer: one sample per seed, raw and denoised.
  render::RenderSettings settings = live.settings();
  const uint32_t base = settings.seed;
  std::vector<float> raw(outcomes[0].oldImage.pixels.size(), 0.0f), denoised = raw;
  for (uint32_t k = 0; k < 3; ++k) {
    settings.seed = base + k;
    live.setSettings(settings);
    live.render(1);
    const auto r = live.readEstimate(), d = live.readImage();
    ASSERT_EQ(r.pixels.size(), raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
      raw[i] += r.pixels[i] / 3.0f;
      denoised[i] += d.pixels[i] / 3.0f;
    }
  }
  double toRaw = 0, toDenoised = 0, rawVsDenoised = 0;
  for (size_t i = 0; i < raw.size(); ++i) {
    if (i % 4 == 3) continue;  // alpha
    // Relative to the value past 1: the two means sum the same samples in another order, and a firefly's
    // (hundreds) rounds differently in its last bits.
    toRaw = std::max(toRaw, double(std::abs(outcomes[0].oldImage.pixels[i] - raw[i])) /
                                std::max(1.0, double(std::abs(raw[i]))));
    toDenoised = std::max(toDenoised, double(std::abs(outcomes[0].oldImage.pixels[i] - denoised[i])));
    rawVsDenoised = std::max(rawVsDenoised, double(std::abs(raw[i] - denoised[i])));
  }
  ASSERT_GT(rawVsDenoised, 1e-2) << "the denoiser changed nothing: the test could not tell the images apart";
  EXPECT_LT(toRaw, 1e-5) << "the A/B image is not the raw mean (off by " << toRaw << ")";
  EXPECT_GT(toDenoised, 1e-2);
  wb::testing::expectNoValidationErrors(*s);
}
