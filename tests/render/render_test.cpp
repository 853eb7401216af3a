// Small renders on the real device (lavapipe here), checked for numbers, not by eye.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

// 0 = hits the plane in the sun, 1 = hits the plane in shadow, 2 = other (box, sky).
int classify(const ShadowScene& s, const render::CameraState& cam, uint32_t w, uint32_t h, float px,
             float py) {
  glm::vec3 o, d;
  cameraRay(cam, w, h, px, py, o, d);
  if (hitBox(o, d, s.boxMin, s.boxMax) >= 0.0f || d.y >= 0.0f) return 2;
  const glm::vec3 p = o + d * (-o.y / d.y);
  if (std::abs(p.x) > 50 || std::abs(p.z) > 50) return 2;
  return hitBox(p + glm::vec3(0, 1e-4f, 0), -s.sunDirection, s.boxMin, s.boxMax) >= 0.0f ? 1 : 0;
}

}  // namespace

TEST(Render, ShadowFallsWhereGeometryBlocksTheSunAndLambertMatchesAnalytic) {
  ShadowScene s = makeShadowScene();
  render::SessionOptions o;
  o.sceneData = s.scene;
  o.settings.width = 64;
  o.settings.height = 64;
  o.settings.envColor = glm::vec3(0.0f);
  auto session = makeSession(o);
  session->render(2);
  const auto img = session->image();
  const auto stats = imageStats(img);
  EXPECT_EQ(stats.nonFinite, 0u);
  EXPECT_EQ(session->pathTracer().readCounters().droppedSamples, 0u);

  // Lambertian plane under a directional light: L = albedo * E * cos(theta) / pi, exactly (no other light).
  const float cosTheta = -s.sunDirection.y;
  const float expectedLit = s.albedo * s.sunRadiance * cosTheta / 3.14159265f;
  const auto& cam = session->sceneCamera();
  int lit = 0, shadowed = 0;
  for (uint32_t y = 0; y < img.height; ++y) {
    for (uint32_t x = 0; x < img.width; ++x) {
      // Only pixels whose whole footprint falls in one class (edges mix classes through the pixel filter).
      int c = classify(s, cam, img.width, img.height, x + 0.5f, y + 0.5f);
      bool uniform = true;
      for (float dy : {0.0f, 1.0f}) {
        for (float dx : {0.0f, 1.0f})
          uniform = uniform && classify(s, cam, img.width, img.height, x + dx, y + dy) == c;
      }
      if (!uniform || c == 2) continue;
      for (int ch = 0; ch < 3; ++ch) {
        const float v = img.at(x, y, ch);
        if (c == 0) {
          EXPECT_NEAR(v, expectedLit, 1e-3f * expectedLit) << "lit pixel " << x << "," << y;
        } else {
          EXPECT_LT(v, 1e-6f) << "shadowed pixel " << x << "," << y;
        }
      }
      (c == 0 ? lit : shadowed)++;
    }
  }
  EXPECT_GT(lit, 500) << "the test should see plenty of sunlit floor";
  EXPECT_GT(shadowed, 50) << "the test should see the box's shadow";
  expectNoValidationErrors(*session);
}

TEST(Render, SharedGltfModelIsNotBlackAndFinite) {
  render::SessionOptions o;
  o.scenePath = (sharedDir() / "assets/gltf/Box/glTF-Embedded/Box.gltf").string();
  o.settings.width = 48;
  o.settings.height = 48;
  auto session = makeSession(o);
  session->render(2);
  const auto stats = imageStats(session->image());
  EXPECT_EQ(stats.nonFinite, 0u);
  EXPECT_GT(stats.mean[0] + stats.mean[1] + stats.mean[2], 0.05);
  expectNoValidationErrors(*session);
}

TEST(Render, TiledDispatchGivesTheSameImage) {
  // The sample streams depend on the pixel, not on the dispatch: any tiling renders the same pixels.
  auto renderWith = [](uint32_t tw, uint32_t th) {
    render::SessionOptions o;
    o.sceneData = makeShadowScene().scene;
    o.settings.width = 40;
    o.settings.height = 24;
    o.settings.tileWidth = tw;
    o.settings.tileHeight = th;
    auto session = makeSession(o);
    session->render(2);
    expectNoValidationErrors(*session);
    return session->image();
  };
  const auto full = renderWith(0, 0), tiled = renderWith(7, 5);
  ASSERT_EQ(full.pixels.size(), tiled.pixels.size());
  for (size_t i = 0; i < full.pixels.size(); ++i) ASSERT_EQ(full.pixels[i], tiled.pixels[i]) << "at " << i;
}

TEST(Render, ASizeUsedBeforeReusesItsImagesClearedAndRendersTheSame) {
  // Going back to a size (the window's preview and full resolution) takes that size's images again instead of
  // allocating, cleared: the image rendered there is the one a fresh session renders.
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings.width = 40;
  o.settings.height = 24;
  auto fresh = makeSession(o);
  fresh->render(2);
  const auto expected = fresh->image();

  auto session = makeSession(o);
  auto& pt = session->pathTracer();
  session->render(3);
  const uint32_t allocated = pt.imageSetsAllocated();
  render::RenderSettings s = pt.settings();
  s.width = 10;
  s.height = 6;
  pt.setSettings(s);
  session->render(1);
  s.width = 40;
  s.height = 24;
  pt.setSettings(s);
  EXPECT_EQ(pt.imageSetsAllocated(), allocated + 1) << "only the new size allocates";
  const auto cleared = session->image();
  for (size_t i = 0; i < cleared.pixels.size(); i += 4) ASSERT_EQ(cleared.pixels[i], 0.0f) << "at " << i;
  session->render(2);
  const auto again = session->image();
  ASSERT_EQ(again.pixels.size(), expected.pixels.size());
  for (size_t i = 0; i < again.pixels.size(); ++i)
    ASSERT_EQ(again.pixels[i], expected.pixels[i]) << "at " << i;
  expectNoValidationErrors(*session);
}

namespace {

// A session with the split path loop forced on or off (WB_SPLIT_SHADOWS; the default is on for GPUs, off on
// lavapipe).
std::unique_ptr<render::RenderSession> sessionSplitting(bool split, const render::SessionOptions& o) {
  ::setenv("WB_SPLIT_SHADOWS", split ? "1" : "0", 1);
  auto session = makeSession(o);
  ::unsetenv("WB_SPLIT_SHADOWS");
  EXPECT_EQ(session->pathTracer().splitsShadows(), split);
  return session;
}

// The accumulation and every AOV of two tracers agree to float rounding (the split sums a sample's light
// samples in another order).
void expectSameAccumulationAndAovs(const render::PathTracer& a, const render::PathTracer& b,
                                   const std::string& what) {
  const auto compare = [&](const std::vector<float>& x, const std::vector<float>& y, const char* name) {
    ASSERT_EQ(x.size(), y.size()) << what << ": " << name;
    size_t differ = 0, first = x.size();
    for (size_t i = 0; i < x.size(); ++i) {
      if (x[i] == y[i] || std::abs(x[i] - y[i]) <= 1e-5f * std::max(std::abs(x[i]), std::abs(y[i]))) continue;
      if (differ++ == 0) first = i;
    }
    EXPECT_EQ(differ, 0u) << what << ": " << name << ", first at " << first << " (" << x[first] << " against "
                          << y[first] << ")";
  };
  compare(a.readAccumulation(), b.readAccumulation(), "accumulation");
  compare(a.readAov(render::Aov::Albedo), b.readAov(render::Aov::Albedo), "albedo");
  compare(a.readAov(render::Aov::Normal), b.readAov(render::Aov::Normal), "normal");
  compare(a.readAov(render::Aov::Info), b.readAov(render::Aov::Info), "info");
  compare(a.readAov(render::Aov::Stats), b.readAov(render::Aov::Stats), "stats");
}

}  // namespace

// Shader execution reordering (where the device has it: NVIDIA's GPUs) regroups the path rays' threads and
// changes nothing they compute: the same accumulation and AOVs as without it, in the one path loop and in the
// split with every shadow ray left in the path loop (a shadow ray's hit must not run closest-hit).
TEST(Render, ReorderedInvocationsTraceTheSameImage) {
  render::SessionOptions o;
  o.settings.width = o.settings.height = 16;
  o.settings.aov = true;
  auto session = [&](const char* reorder, const char* split, const char* slots) {
    ::setenv("WB_INVOCATION_REORDER", reorder, 1);
    ::setenv("WB_SPLIT_SHADOWS", split, 1);
    ::setenv("WB_SPLIT_SLOTS", slots, 1);
    auto s = makeSession(o);
    for (const char* v : {"WB_INVOCATION_REORDER", "WB_SPLIT_SHADOWS", "WB_SPLIT_SLOTS"}) ::unsetenv(v);
    return s;
  };
  if (session("0", "0", "0")->context().invocationReorderSupport() == "unsupported")
    GTEST_SKIP() << "the device has no VK_NV_ray_tracing_invocation_reorder";
  for (const char* split : {"0", "1"}) {
    auto plain = session("0", split, "0"), reordered = session("1", split, "0");
    EXPECT_FALSE(plain->pathTracer().reordersInvocations());
    EXPECT_TRUE(reordered->pathTracer().reordersInvocations());
    plain->render(2);
    reordered->render(2);
    expectSameAccumulationAndAovs(plain->pathTracer(), reordered->pathTracer(),
                                  std::string("reordered, split ") + split);
    EXPECT_EQ(plain->pathTracer().readCounters().rayCount, reordered->pathTracer().readCounters().rayCount);
    expectNoValidationErrors(*reordered);
  }
}

// Where the path tracer splits its shadow rays (the default on GPUs), renders with AOVs (the window's views
// and the denoiser's guides) split too, and the shadow launch writes the one loop's AOVs after adding the
// light samples: on the default scene (alpha-tested leaves) with the denoiser turned on after two samples
// (the split's records grow to hold the AOVs), and under an infinite sun, where the NaN/Inf source of a pixel
// whose camera ray hits the sphere's lit side is its first vertex's light sample (bounce 0), traced by the
// shadow launch, or without next-event estimation under an infinite environment, where it is a path ray's
// (the split's raygen). The passes stay the same objects in the same order while the AOVs turn on and off:
// the live-edit loop and the A/B stand-ins keep pointers to them and their indices.
TEST(Render, SplitShadowsWriteTheOneLoopsAovsAndKeepThePasses) {
  render::SessionOptions o;
  o.settings.width = o.settings.height = 16;
  auto loop = sessionSplitting(false, o), split = sessionSplitting(true, o);
  const auto passes = split->pathTracer().passes();
  EXPECT_FALSE(split->pathTracer().splitsAovs()) << "a plain render's split carries no AOVs";
  loop->render(2);
  split->render(2);
  render::RenderSettings settings = split->pathTracer().settings();
  settings.denoise = true;
  for (auto* s : {loop.get(), split.get()}) {
    s->pathTracer().setSettings(settings);
    s->render(3);
  }
  EXPECT_TRUE(split->pathTracer().splitsShadows());
  EXPECT_GT(split->pathTracer().passes().size(), passes.size()) << "the denoiser's passes";
  expectSameAccumulationAndAovs(loop->pathTracer(), split->pathTracer(), "default scene, denoised");
  EXPECT_TRUE(split->pathTracer().splitsAovs());
  const uint32_t samples = split->pathTracer().samplesAccumulated();
  settings.denoise = false;
  split->pathTracer().setSettings(settings);
  EXPECT_EQ(split->pathTracer().samplesAccumulated(), samples)
      << "turning the denoiser off keeps the accumulation";
  split->render(1);
  EXPECT_TRUE(split->pathTracer().splitsShadows());
  const auto after = split->pathTracer().passes();
  EXPECT_TRUE(std::equal(passes.begin(), passes.end(), after.begin())) << "the passes stay the same objects";
  EXPECT_EQ(split->pathTracer().readCounters().droppedSamples, 0u);
  // Several samples per launch (without AOVs) on the variant kept: as the one loop, it leaves the AOVs alone
  // (the samples of a launch would race on them).
  const auto aovsBefore = split->pathTracer().readAov(render::Aov::Stats);
  settings.samplesPerLaunch = 4;
  split->pathTracer().setSettings(settings);
  EXPECT_TRUE(split->pathTracer().splitsAovs());
  split->render(4);
  EXPECT_EQ(split->pathTracer().readAov(render::Aov::Stats), aovsBefore) << "a launch of several samples";
  EXPECT_EQ(split->pathTracer().readCounters().droppedSamples, 0u);
  expectNoValidationErrors(*loop);
  expectNoValidationErrors(*split);

  // An infinite sun over a finite environment: only next-event estimation's light samples are infinite.
  render::SessionOptions infinite;
  infinite.sceneData = makeFurnaceScene(lambert(glm::vec3(0.5f)));
  gpu::DirectionalLight sun{};
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
  sun.cosAngularRadius = 1.0f;
  sun.radiance = glm::vec3(std::numeric_limits<float>::infinity());
  infinite.sceneData->lights.push_back(sun);
  infinite.settings.width = infinite.settings.height = 16;
  infinite.settings.envColor = glm::vec3(0.5f);
  infinite.settings.aov = true;
  loop = sessionSplitting(false, infinite);
  split = sessionSplitting(true, infinite);
  loop->render(2);
  split->render(2);
  expectSameAccumulationAndAovs(loop->pathTracer(), split->pathTracer(), "infinite sun");
  const auto stats = split->pathTracer().readAov(render::Aov::Stats);
  size_t lit = 0, none = 0;
  for (size_t i = 0; i < 256; ++i) {
    const float bounce = stats[4 * i + 3];
    EXPECT_TRUE(bounce == 0.0f || bounce == float(WB_NO_NON_FINITE)) << "pixel " << i << ": " << bounce;
    lit += bounce == 0.0f;
    none += bounce == float(WB_NO_NON_FINITE);
  }
  EXPECT_GT(lit, 20u) << "pixels whose first vertex's sun sample is infinite (bounce 0, the shadow launch's)";
  EXPECT_GT(none, 20u) << "pixels that miss the sphere or face away from the sun";
  expectNoValidationErrors(*loop);
  expectNoValidationErrors(*split);

  // An infinite environment without next-event estimation: the path's own contributions turn the samples
  // infinite (bounce 0 for a camera ray that misses the sphere, 1 for one whose continuation escapes), which
  // the split's raygen writes to its record as they happen.
  infinite.sceneData = makeFurnaceScene(lambert(glm::vec3(0.5f)));
  infinite.settings.envColor = glm::vec3(3.0e38f);
  infinite.settings.envIntensity = 10.0f;
  infinite.settings.nee = false;
  loop = sessionSplitting(false, infinite);
  split = sessionSplitting(true, infinite);
  loop->render(2);
  split->render(2);
  expectSameAccumulationAndAovs(loop->pathTracer(), split->pathTracer(), "infinite environment");
  const auto escaped = split->pathTracer().readAov(render::Aov::Stats);
  size_t atOne = 0;
  for (size_t i = 0; i < 256; ++i) atOne += escaped[4 * i + 3] == 1.0f;
  EXPECT_GT(atOne, 20u) << "pixels whose continuation escapes to the infinite environment";
  expectNoValidationErrors(*loop);
  expectNoValidationErrors(*split);
}
