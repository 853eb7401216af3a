// Error per sample against Blender Cycles (issue 20): the Cornell box in the default configuration at 16 spp,
// relMSE (eps 0.01) against the Cycles reference, mean over seeds. A change that makes the path tracer need
// more samples for the same error (a worse sampler, light sampling or Russian roulette) fails; so does the
// configuration from before issue 20, run here too so the bound is known to tell the two apart.
//
// Cost: 64x64 renders (each pixel covers a 4x4 block of the 256x256 reference, which is box-downsampled to
// match), 16 spp, 8 seeds per configuration: a few seconds on lavapipe.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/paths.h"
#include "eval/metrics.h"
#include "gpu_fixture.h"

using namespace wb;
using namespace wb::testing;

namespace {

struct Spread {
  double mean = 0, sd = 0, min = 1e30, max = 0;
};

Spread relMseOverSeeds(render::RenderSession& session, render::RenderSettings settings,
                       const eval::ImageRGBA& reference, uint32_t seeds, uint32_t spp) {
  std::vector<double> values;
  for (uint32_t k = 0; k < seeds; ++k) {
    settings.seed = 1 + k;
    session.pathTracer().setSettings(settings);
    session.render(spp);
    EXPECT_EQ(session.pathTracer().readCounters().droppedSamples, 0u);
    values.push_back(eval::relMse(session.image(), reference, 0.01));
  }
  Spread s;
  for (double v : values) {
    s.mean += v / double(values.size());
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
  }
  for (double v : values) s.sd += (v - s.mean) * (v - s.mean) / double(values.size() - 1);
  s.sd = std::sqrt(s.sd);
  return s;
}

}  // namespace

TEST(ErrorPerSample, CornellAt16SppAgainstCycles) {
  const auto dir = sharedDir() / "reference";
  const eval::ImageRGBA reference = eval::downsampleTo(eval::readExr(dir / "cornell_cycles.exr"), 64, 64);
  render::SessionOptions o;
  o.scenePath = (dir / "cornell.gltf").string();
  o.settings.width = o.settings.height = 64;
  o.settings.envColor = glm::vec3(0.0f);  // the reference's settings: --env-color 0,0,0 --max-bounces 64
  o.settings.maxBounces = 64;
  auto session = makeSession(o);
  constexpr uint32_t kSeeds = 8, kSpp = 16;
  const Spread now = relMseOverSeeds(*session, o.settings, reference, kSeeds, kSpp);
  // Before issue 20: Sobol + blue-noise rotation, uniform area sampling of the light, survival proportional
  // to the throughput. (Its light point dimensions and BRDF lobe choice are today's, slightly better than
  // then.) The define is a shader variant: a session of its own.
  render::SessionOptions b = o;
  b.settings.sampler = render::SamplerKind::Sobol;
  b.settings.rrExponent = 1.0f;
  b.settings.rrStart = 2;
  b.settings.defines = {{"WB_EMITTER_SOLID_ANGLE", "0"}};
  auto beforeSession = makeSession(b);
  const Spread old = relMseOverSeeds(*beforeSession, b.settings, reference, kSeeds, kSpp);
  std::printf(
      "relMSE at %u spp, 64x64, %u seeds: default %.5f (sd %.5f, %.5f..%.5f); before issue 20 %.5f (sd "
      "%.5f)\n",
      kSpp, kSeeds, now.mean, now.sd, now.min, now.max, old.mean, old.sd);
  // The bound, from the measured spread (lavapipe, 2026-12-02): the default configuration 0.0199 (per-seed sd
  // 0.00065, so the 8-seed mean's sd is ~0.0002; seeds 0.0192..0.0211); before issue 20 0.0394 (sd 0.0028).
  // 0.0225 is 13% (~10 sd) above today's mean and far below the old configuration's.
  constexpr double kBound = 0.0225;
  EXPECT_LT(now.mean, kBound) << "error per sample regressed";
  EXPECT_GT(old.mean, kBound) << "the bound no longer separates the old configuration from the default";
  expectNoValidationErrors(*session);
  expectNoValidationErrors(*beforeSession);
}
