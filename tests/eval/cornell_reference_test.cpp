// Our render of the Cornell box against an independent reference (Blender Cycles, 2 x 8192 spp, 256x256):
// 64x64 renders from independent seeds, compared after a box downsample to 16x16 (the reference is
// downsampled 16x to the same size) in the per-channel means and by the per-pixel variance-aware test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/paths.h"
#include "eval/metrics.h"
#include "gpu_runs.h"

using namespace wb;
using namespace wb::testing;

TEST(CornellReference, AgreesWithCyclesWithinNoise) {
  const auto dir = sharedDir() / "reference";
  const eval::ImageRGBA cycles = eval::readExr(dir / "cornell_cycles.exr");
  ASSERT_EQ(cycles.width, 256u);
  render::SessionOptions o;
  o.scenePath = (dir / "cornell.gltf").string();
  o.settings.width = o.settings.height = 64;
  o.settings.envColor = glm::vec3(0.0f);  // --env-color 0,0,0
  o.settings.maxBounces = 64;             // --max-bounces 64
  auto session = makeSession(o);
  // 8 runs x 384 spp (~25 s on lavapipe), PCG: the standard error of each channel's image mean is ~0.03%.
  const auto runs = downsampleAll(renderRuns(*session, o.settings, 8, 384, 1), 4);
  const auto ours = eval::estimateFromRuns(runs);
  const auto reference = eval::downsampleTo(cycles, 16, 16);

  const eval::Rgb m = eval::meanRgb(ours.mean), r = eval::meanRgb(reference);
  for (int c = 0; c < 3; ++c) {
    // Standard error of our image mean from the run-to-run spread of the run means.
    double mean = 0, sq = 0;
    for (const auto& run : runs) mean += eval::meanRgb(run)[c] / double(runs.size());
    for (const auto& run : runs) sq += std::pow(eval::meanRgb(run)[c] - mean, 2.0);
    const double se = std::sqrt(sq / double(runs.size() - 1) / double(runs.size()));
    const double rel = m[c] / r[c] - 1.0;
    std::printf("channel %d: ours %.5f (se %.5f, %.3f%%) cycles %.5f: %+.3f%% (%+.1f se)\n", c, m[c], se,
                100.0 * se / m[c], r[c], 100.0 * rel, (m[c] - r[c]) / se);
    // Measured (8 x 384 spp, PCG): se ~0.03% per channel; ours is +0.08..+0.10% brighter than Cycles (3-4 se:
    // a real but tiny residual between the two renderers). Investigated: it is not the image border (pixel
    // filter), it is the same in every quarter of the image within noise and in every channel, so it is no
    // colour, emitter-side or bounce-count effect; what remains is how each renderer offsets its rays near
    // the box's edges, which we cannot inspect in Cycles. The README's bound for a correct render is 1%; we
    // hold 0.3% (~10 se, 3x the residual): a back-face emitter (+3%) or a lost bounce fails by far.
    EXPECT_LT(std::abs(rel), 0.003) << "channel " << c;
  }
  // Per-pixel structure: the Cycles reference's own noise (README: relMSE 1.4e-5 per 256x256 pixel, i.e.
  // variance ~1.4e-5 (b^2 + 0.01)) averaged over the 16 x 16 block.
  eval::MeanEstimate ref = eval::exactReference(reference);
  for (size_t i = 0; i < ref.varianceOfMean.pixels.size(); ++i) {
    const double b = reference.pixels[i];
    ref.varianceOfMean.pixels[i] = float(1.4e-5 * (b * b + 0.01) / 256.0);
  }
  ref.dof = 1e9;  // a model, not an estimate from runs
  const auto t = eval::statisticalTest(ours, ref);
  std::printf("per-pixel test at 16x16: %s\n", t.summary().c_str());
  EXPECT_TRUE(t.pixelTestPass) << t.summary();
  EXPECT_TRUE(t.chiSquarePass) << t.summary();
  // relMSE after the box downsample (measured 2.2e-5: noise plus the 0.1% residual's 1e-6); a back-face
  // emitter (+3% overall, far more near the light) or a lost bounce is above 1e-3.
  const double relMse = eval::relMse(ours.mean, reference);
  std::printf("relMSE at 16x16: %.3g\n", relMse);
  EXPECT_LT(relMse, 1e-4);

  // The default configuration (owen sampler, solid-angle light sampling, square-root Russian roulette)
  // converges to the same means: within 0.3% of Cycles per channel (issue 20's bar). Its runs are so much
  // less noisy (se ~0.007% from 8 x 384 spp) that the residual above shows at 6-8 se (measured +0.047 +0.045
  // +0.032%), so the per-pixel test is left to the PCG runs; 8 x 128 spp here.
  const auto owenRuns = renderRuns(*session, o.settings, 8, 128, 11, render::SamplerKind::Owen);
  const eval::Rgb mo = eval::meanRgb(eval::estimateFromRuns(owenRuns).mean);
  const eval::Rgb full = eval::meanRgb(cycles);
  for (int c = 0; c < 3; ++c) {
    const double rel = mo[c] / full[c] - 1.0;
    std::printf("default configuration, channel %d: %.5f vs cycles %.5f: %+.3f%%\n", c, mo[c], full[c],
                100.0 * rel);
    EXPECT_LT(std::abs(rel), 0.003) << "channel " << c;
  }
  expectNoValidationErrors(*session);
}
