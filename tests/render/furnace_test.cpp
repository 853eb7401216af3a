// The white furnace on the GPU: a closed white Lambertian object in a uniform environment of radiance 1
// renders 1 everywhere, whatever the sampler (owen, the default; sobol; pcg) and sampling strategy (NEE +
// MIS, BRDF only, light only) and with or without Russian roulette.
#include <gtest/gtest.h>

#include "gpu_fixture.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

double furnaceMean(render::RenderSettings settings, uint32_t spp) {
  render::SessionOptions o;
  o.sceneData = makeFurnaceScene(lambert(glm::vec3(1.0f)));
  settings.width = 32;
  settings.height = 32;
  settings.envColor = glm::vec3(1.0f);
  settings.maxBounces = 64;
  o.settings = settings;
  auto session = makeSession(o);
  session->render(spp);
  const auto img = session->image();
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(img.pixels[4 * i + c]));
      sum += img.pixels[4 * i + c];
      n++;
    }
  }
  EXPECT_EQ(session->pathTracer().readCounters().droppedSamples, 0u);
  expectNoValidationErrors(*session);
  return sum / double(n);
}

}  // namespace

TEST(Furnace, NeeWithMis) {
  EXPECT_NEAR(furnaceMean({}, 64), 1.0, 0.005);
}

TEST(Furnace, BrdfSamplingOnly) {
  render::RenderSettings s;
  s.nee = false;
  EXPECT_NEAR(furnaceMean(s, 64), 1.0, 0.005);
}

TEST(Furnace, LightSamplingOnly) {
  render::RenderSettings s;
  s.mis = false;
  EXPECT_NEAR(furnaceMean(s, 64), 1.0, 0.005);
}

TEST(Furnace, WithoutRussianRoulette) {
  render::RenderSettings s;
  s.russianRoulette = false;
  EXPECT_NEAR(furnaceMean(s, 64), 1.0, 0.005);
}

TEST(Furnace, SobolSampler) {
  render::RenderSettings s;
  s.sampler = render::SamplerKind::Sobol;
  EXPECT_NEAR(furnaceMean(s, 64), 1.0, 0.005);
}

TEST(Furnace, OwenSamplerRussianRouletteFromTheFirstBounce) {
  render::RenderSettings s;
  s.sampler = render::SamplerKind::Owen;
  s.rrStart = 1;
  s.rrExponent = 0.5f;
  EXPECT_NEAR(furnaceMean(s, 64), 1.0, 0.005);
}

TEST(Furnace, PcgSampler) {
  render::RenderSettings s;
  s.sampler = render::SamplerKind::Pcg;
  EXPECT_NEAR(furnaceMean(s, 64), 1.0, 0.005);
}
