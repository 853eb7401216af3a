// Independent GPU runs (different seeds) of one session, for the statistical tests.
#pragma once
#include <vector>

#include "gpu_fixture.h"

namespace wb::testing {

inline std::vector<eval::ImageRGBA> renderRuns(render::RenderSession& session,
                                               render::RenderSettings settings, uint32_t runs, uint32_t spp,
                                               uint32_t firstSeed) {
  // Independent runs need independent randomisations: with the Sobol sampler the seed only shifts every
  // dimension's Cranley-Patterson rotation by the same constant (seed x golden ratio), so runs of one pixel
  // are a one-parameter family, their spread underestimates the pixel's error and the per-pixel test fails.
  // PCG samples are independent across seeds.
  settings.sampler = render::SamplerKind::Pcg;
  std::vector<eval::ImageRGBA> out;
  for (uint32_t r = 0; r < runs; ++r) {
    settings.seed = firstSeed + r;
    session.pathTracer().setSettings(settings);
    session.render(spp);
    EXPECT_EQ(session.pathTracer().readCounters().droppedSamples, 0u);
    out.push_back(session.image());
  }
  return out;
}

inline std::vector<eval::ImageRGBA> downsampleAll(const std::vector<eval::ImageRGBA>& images, uint32_t k) {
  std::vector<eval::ImageRGBA> out;
  for (const auto& i : images) out.push_back(eval::boxDownsample(i, k));
  return out;
}

}  // namespace wb::testing
