// The heat maps' data (the path tracer's AOVs behind the window's bounces, rr_end, variance and nan_source
// views), checked against the settings that bound them and against the path inspector's records of the same
// samples.
#include <gtest/gtest.h>

#include <cmath>

#include "gpu_fixture.h"
#include "render/path_inspector.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

constexpr uint32_t kSize = 24;

render::SessionOptions defaultScene(render::RenderSettings s = {}) {
  render::SessionOptions o;
  s.width = s.height = kSize;
  s.aov = true;
  o.settings = s;
  o.quiet = true;
  return o;
}

float luminance(const glm::vec3& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

}  // namespace

TEST(HeatMaps, PathLengthIsBoundedByMaxBounces) {
  double meanOne = 0, meanFour = 0;
  for (uint32_t maxBounces : {1u, 4u}) {
    render::RenderSettings s;
    s.maxBounces = maxBounces;
    auto session = makeSession(defaultScene(s));
    session->render(4);
    const auto info = session->pathTracer().readAov(render::Aov::Info);
    double sum = 0, longest = 0;
    for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
      const double bounces = info[4 * i + 3] - 1.0;  // rays per path: the camera ray and one per bounce
      EXPECT_GE(bounces, -1e-3) << "pixel " << i;
      EXPECT_LE(bounces, maxBounces + 1e-3) << "pixel " << i;
      sum += bounces;
      longest = std::max(longest, bounces);
    }
    (maxBounces == 1 ? meanOne : meanFour) = sum / (kSize * kSize);
    if (maxBounces == 4) {
      EXPECT_GT(longest, 2.0) << "the room keeps paths going";
    }
    expectNoValidationErrors(*session);
  }
  EXPECT_GT(meanFour, meanOne + 0.5);
}

TEST(HeatMaps, RussianRouletteEndMatchesTheInspectedPaths) {
  render::RenderSettings s;
  s.maxBounces = 6;
  s.rrStart = 2;
  s.rrMin = s.rrMax = 0.5f;  // a coin at every bounce from 2 on
  auto session = makeSession(defaultScene(s));
  // Pixel 12,14 recorded by the inspector while the whole image accumulates the same samples.
  render::InspectRequest r;
  r.x = 12;
  r.y = 14;
  r.samples = 16;
  session->pathTracer().setInspection(r);
  session->render(16);
  const auto stats = session->pathTracer().readAov(render::Aov::Stats);
  size_t ended = 0;
  for (size_t i = 0; i < size_t(kSize) * kSize; ++i) {
    const float fraction = stats[4 * i + 1], bounceSum = stats[4 * i + 2];
    EXPECT_GE(fraction, 0.0f);
    EXPECT_LE(fraction, 1.0f + 1e-6f);
    if (fraction <= 0.0f) continue;
    ++ended;
    // Never before rr_start, never at the last bounce (max bounces ends the path there first).
    EXPECT_GE(bounceSum / fraction, 2.0f - 1e-5f) << "pixel " << i;
    EXPECT_LE(bounceSum / fraction, 5.0f + 1e-5f) << "pixel " << i;
  }
  EXPECT_GT(ended, kSize * kSize / 4);

  const auto samples = render::inspectedSamples(session->pathTracer().readInspection());
  ASSERT_EQ(samples.size(), 16u);
  double rrEnds = 0, rrBounces = 0;
  for (const auto& smp : samples) {
    if (smp.record.end != WB_INSPECT_END_RUSSIAN_ROULETTE) continue;
    rrEnds += 1;
    rrBounces += double(smp.vertices.size() - 1);  // RR ends the path at its last vertex
  }
  const size_t p = (size_t(14) * kSize + 12) * 4;
  EXPECT_NEAR(stats[p + 1], rrEnds / 16.0, 1e-5);
  EXPECT_NEAR(stats[p + 2], rrBounces / 16.0, 1e-5);
  EXPECT_GT(rrEnds, 0.0);

  // Without Russian roulette no path ends by it.
  s.russianRoulette = false;
  session->pathTracer().setSettings(defaultScene(s).settings);
  session->render(2);
  const auto off = session->pathTracer().readAov(render::Aov::Stats);
  for (size_t i = 0; i < size_t(kSize) * kSize; ++i) EXPECT_EQ(off[4 * i + 1], 0.0f) << "pixel " << i;
  expectNoValidationErrors(*session);
}

TEST(HeatMaps, VarianceDataIsTheMeanSquareOfTheInspectedSamples) {
  auto session = makeSession(defaultScene());
  for (auto [x, y] : {std::pair{12u, 14u}, std::pair{4u, 19u}}) {
    render::InspectRequest r;
    r.x = x;
    r.y = y;
    r.samples = 12;
    session->pathTracer().setInspection(r);
    session->render(12);
    const auto stats = session->pathTracer().readAov(render::Aov::Stats);
    const auto samples = render::inspectedSamples(session->pathTracer().readInspection());
    ASSERT_EQ(samples.size(), 12u);
    double meanSquare = 0, mean = 0;
    for (const auto& s : samples) {
      const double l = luminance(s.record.radiance);
      meanSquare += l * l / 12.0;
      mean += l / 12.0;
    }
    const float stored = stats[(size_t(y) * kSize + x) * 4];
    EXPECT_NEAR(stored, meanSquare, 1e-5 * std::max(1.0, meanSquare));
    EXPECT_GT(meanSquare - mean * mean, 1e-6) << "the default scene's pixels are noisy at 12 spp";
  }
  // A white furnace sampled by the BRDF alone has no variance: every sample is 1.
  render::SessionOptions o;
  o.sceneData = makeFurnaceScene(lambert(glm::vec3(1.0f)));
  o.settings.width = o.settings.height = 8;
  o.settings.envColor = glm::vec3(1.0f);
  o.settings.nee = false;
  o.settings.aov = true;
  auto furnace = makeSession(o);
  furnace->render(4);
  const auto stats = furnace->pathTracer().readAov(render::Aov::Stats);
  const auto accum = furnace->pathTracer().readAccumulation();
  for (size_t i = 0; i < 64; ++i) {
    const float l = luminance(glm::vec3(accum[4 * i], accum[4 * i + 1], accum[4 * i + 2]));
    EXPECT_NEAR(stats[4 * i] - l * l, 0.0f, 1e-4f) << "pixel " << i;
  }
  expectNoValidationErrors(*session);
  expectNoValidationErrors(*furnace);
}

TEST(HeatMaps, NanSourceIsTheBounceWhereTheSampleWentInfinite) {
  // An infinite environment and no next-event estimation: a camera ray that misses the sphere is infinite at
  // bounce 0; one that hits it at bounce 1, when its continuation escapes.
  render::SessionOptions o;
  o.sceneData = makeFurnaceScene(lambert(glm::vec3(0.5f)));
  o.settings.width = o.settings.height = 16;
  o.settings.envColor = glm::vec3(3.0e38f);
  o.settings.envIntensity = 10.0f;
  o.settings.nee = false;
  o.settings.aov = true;
  auto session = makeSession(o);
  session->render(2);
  const auto stats = session->pathTracer().readAov(render::Aov::Stats);
  const auto normal = session->pathTracer().readAov(render::Aov::Normal);
  size_t zero = 0, one = 0;
  for (size_t i = 0; i < 256; ++i) {
    const float bounce = stats[4 * i + 3], firstHit = normal[4 * i + 3];
    EXPECT_TRUE(bounce == 0.0f || bounce == 1.0f) << "pixel " << i << ": " << bounce;
    if (firstHit < 0.0f) {
      EXPECT_EQ(bounce, 0.0f) << "pixel " << i << " misses the sphere";
    }
    if (firstHit > 0.0f && bounce == 1.0f) ++one;
    zero += bounce == 0.0f;
  }
  EXPECT_GT(one, 100u);
  EXPECT_GT(zero, 0u);
  // A finite scene has no source anywhere.
  o.settings.envColor = glm::vec3(1.0f);
  o.settings.envIntensity = 1.0f;
  session->setEnvironment(o.settings);
  session->pathTracer().setSettings(o.settings);
  session->render(2);
  const auto finite = session->pathTracer().readAov(render::Aov::Stats);
  for (size_t i = 0; i < 256; ++i) EXPECT_EQ(finite[4 * i + 3], float(WB_NO_NON_FINITE)) << "pixel " << i;
  expectNoValidationErrors(*session);
}
