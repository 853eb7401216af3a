// Several samples per ray tracing launch (issue 29: filling a GPU at small sizes) accumulate into the same
// image as one sample per launch: the same samples in the same order.
#include <gtest/gtest.h>

#include <cmath>

#include "gpu_fixture.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

struct Rendered {
  eval::ImageRGBA image;
  gpu::Counters counters;
};

Rendered renderWithLaunchDepth(uint32_t samplesPerLaunch, uint32_t spp) {
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings.width = 24;
  o.settings.height = 20;
  o.settings.samplesPerLaunch = samplesPerLaunch;
  auto session = makeSession(o);
  EXPECT_EQ(session->pathTracer().samplesPerLaunch(), samplesPerLaunch);
  session->render(spp);
  EXPECT_EQ(session->pathTracer().samplesAccumulated(), spp);
  Rendered r{session->image(), session->pathTracer().readCounters()};
  expectNoValidationErrors(*session);
  return r;
}

}  // namespace

// 7 samples in launches of 3 (3 + 3 + 1: the resolve pass, then a plain launch) against 7 launches of one:
// the same paths (the same ray counts) and the same running average per pixel.
TEST(SamplesPerLaunch, SeveralSamplesPerLaunchAccumulateTheSameImage) {
  const Rendered one = renderWithLaunchDepth(1, 7);
  const Rendered three = renderWithLaunchDepth(3, 7);
  EXPECT_EQ(one.counters.pathCount, 24u * 20u * 7u);
  EXPECT_EQ(three.counters.pathCount, one.counters.pathCount);
  EXPECT_EQ(three.counters.rayCount, one.counters.rayCount);
  EXPECT_EQ(three.counters.shadowRayCount, one.counters.shadowRayCount);
  EXPECT_EQ(three.counters.droppedSamples, 0u);
  ASSERT_EQ(one.image.pixels.size(), three.image.pixels.size());
  size_t differ = 0;
  double sum = 0;
  for (size_t i = 0; i < one.image.pixels.size(); ++i) {
    const float a = one.image.pixels[i], b = three.image.pixels[i];
    sum += a;
    if (std::abs(a - b) > 1e-5f * std::max(1.0f, std::abs(a))) ++differ;
  }
  EXPECT_GT(sum, 0.0);
  EXPECT_EQ(differ, 0u);
}

TEST(SamplesPerLaunch, TheDevicesChoiceIsOneOnACpuAndAlwaysOneWithAovs) {
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings.width = o.settings.height = 16;
  o.settings.samplesPerLaunch = 0;
  auto session = makeSession(o);
  auto& pt = session->pathTracer();
  if (session->context().policy().compilesAtFirstDispatch)
    EXPECT_EQ(pt.samplesPerLaunch(), 1u);
  else
    EXPECT_EQ(pt.samplesPerLaunch(), 16u);  // 256 pixels: the cap
  render::RenderSettings s = pt.settings();
  s.samplesPerLaunch = 8;
  s.aov = true;
  pt.setSettings(s);
  EXPECT_EQ(pt.samplesPerLaunch(), 1u);
}

// The cost, inspecting and asserts variants write per-pixel records one sample at a time (the cost image's
// running mean and median, the inspector's slots, the asserts' failures in sample order): while one is on,
// every launch traces one sample whatever the settings ask.
TEST(SamplesPerLaunch, TheMeasuringVariantsTraceOneSampleAtATime) {
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings.width = o.settings.height = 16;
  o.settings.samplesPerLaunch = 4;
  auto session = makeSession(o);
  auto& pt = session->pathTracer();
  EXPECT_EQ(pt.samplesPerLaunch(), 4u);
  for (const bool cost : {true, false}) {
    render::Instrumentation i;
    i.cost = cost;
    i.asserts = !cost;
    pt.setInstrumentation(i);
    EXPECT_EQ(pt.samplesPerLaunch(), 1u) << (cost ? "cost" : "asserts");
    session->render(3);
    EXPECT_EQ(pt.samplesAccumulated(), 3u);
  }
  pt.setInstrumentation({});
  EXPECT_EQ(pt.samplesPerLaunch(), 4u);
  render::InspectRequest r;
  r.x = r.y = 8;
  r.samples = 4;
  pt.setInspection(r);
  EXPECT_EQ(pt.samplesPerLaunch(), 1u);
  pt.setInspection(std::nullopt);
  EXPECT_EQ(pt.samplesPerLaunch(), 4u);
  expectNoValidationErrors(*session);
}

// pass_ms is per sample: a launch of several samples is one timed scope, its time divided by its samples.
TEST(SamplesPerLaunch, PassTimesArePerSample) {
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings.width = o.settings.height = 16;
  o.settings.samplesPerLaunch = 4;
  auto session = makeSession(o);
  vk::GpuTimer* timer = session->renderer().passTimer();
  ASSERT_NE(timer, nullptr);
  if (!timer->supported()) GTEST_SKIP() << "the queue writes no timestamps";
  session->render(8);  // resets the totals first: two launches of 4
  ASSERT_EQ(timer->totals().size(), 1u);
  const vk::PassTime& t = timer->totals().front();
  EXPECT_EQ(t.pass, "pathtracer");
  EXPECT_EQ(t.scopes, 2u);
  EXPECT_EQ(t.samples, 8u);
  EXPECT_EQ(timer->rounds(), 2u);
  const auto medians = timer->medians();
  ASSERT_EQ(medians.size(), 1u);
  EXPECT_GT(medians.front().ms, 0.0);
  expectNoValidationErrors(*session);
}
