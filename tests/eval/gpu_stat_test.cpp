// The variance-aware statistical test on real renders: two sets of independent runs of the same scene
// (different seeds) pass; the same runs scaled by 1.02 (a 2% bias) fail.
#include <gtest/gtest.h>

#include <cstdio>

#include "common/paths.h"
#include "eval/metrics.h"
#include "gpu_runs.h"

using namespace wb;
using namespace wb::testing;

TEST(StatisticalTestGpu, SeedsPassTwoPercentBiasFails) {
  render::SessionOptions o;
  o.scenePath = (sharedDir() / "reference/cornell.gltf").string();
  o.settings.width = o.settings.height = 64;
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.maxBounces = 64;
  auto session = makeSession(o);
  // 8 runs of 64 spp per set: the image mean's standard error is ~0.15%, so 2% is > 8 standard errors.
  const auto a = downsampleAll(renderRuns(*session, o.settings, 8, 64, 1), 2);
  const auto b = downsampleAll(renderRuns(*session, o.settings, 8, 64, 101), 2);
  const auto same = eval::statisticalTest(eval::estimateFromRuns(a), eval::estimateFromRuns(b));
  std::printf("different seeds: %s\n", same.summary().c_str());
  EXPECT_TRUE(same.pass) << same.summary();

  auto scaled = a;
  for (auto& img : scaled)
    for (float& v : img.pixels) v *= 1.02f;
  const auto biased = eval::statisticalTest(eval::estimateFromRuns(scaled), eval::estimateFromRuns(b));
  std::printf("scaled by 1.02: %s\n", biased.summary().c_str());
  EXPECT_FALSE(biased.pass) << biased.summary();
  EXPECT_FALSE(biased.meanTestPass);
  expectNoValidationErrors(*session);
}

// The same with the owen sampler (the default): its seeds are independent randomisations, so runs pass the
// per-pixel test against PCG runs (no sampler-dependent bias) and against each other, and a 2% bias fails.
TEST(StatisticalTestGpu, OwenRunsAgreeWithPcgRuns) {
  render::SessionOptions o;
  o.scenePath = (sharedDir() / "reference/cornell.gltf").string();
  o.settings.width = o.settings.height = 64;
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.maxBounces = 64;
  auto session = makeSession(o);
  const auto owenA = downsampleAll(renderRuns(*session, o.settings, 8, 64, 1, render::SamplerKind::Owen), 2);
  const auto owenB =
      downsampleAll(renderRuns(*session, o.settings, 8, 64, 101, render::SamplerKind::Owen), 2);
  const auto pcg = downsampleAll(renderRuns(*session, o.settings, 8, 64, 201), 2);
  const auto seeds = eval::statisticalTest(eval::estimateFromRuns(owenA), eval::estimateFromRuns(owenB));
  std::printf("owen, different seeds: %s\n", seeds.summary().c_str());
  EXPECT_TRUE(seeds.pass) << seeds.summary();
  const auto vsPcg = eval::statisticalTest(eval::estimateFromRuns(owenA), eval::estimateFromRuns(pcg));
  std::printf("owen vs pcg: %s\n", vsPcg.summary().c_str());
  EXPECT_TRUE(vsPcg.pass) << vsPcg.summary();
  auto scaled = owenA;
  for (auto& img : scaled)
    for (float& v : img.pixels) v *= 1.02f;
  const auto biased = eval::statisticalTest(eval::estimateFromRuns(scaled), eval::estimateFromRuns(owenB));
  std::printf("owen scaled by 1.02: %s\n", biased.summary().c_str());
  EXPECT_FALSE(biased.pass) << biased.summary();
  expectNoValidationErrors(*session);
}
