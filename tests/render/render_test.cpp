// Small renders on the real device (lavapipe here), checked for numbers, not by eye.
#include <gtest/gtest.h>

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

// Where the path tracer splits its shadow rays (WB_SPLIT_SHADOWS=1 here; the default on GPUs), its passes stay
// the same objects in the same order while AOVs turn the split off and on again: the live-edit loop and the A/B
// stand-ins keep pointers to them and their indices.
TEST(Render, SplitShadowsKeepThePassesWhileAovsTurnItOffAndOn) {
  ::setenv("WB_SPLIT_SHADOWS", "1", 1);
  render::SessionOptions o;
  o.settings.width = o.settings.height = 16;
  auto session = makeSession(o);
  ::unsetenv("WB_SPLIT_SHADOWS");
  render::PathTracer& tracer = session->pathTracer();
  ASSERT_TRUE(tracer.splitsShadows());
  const auto before = tracer.passes();
  render::RenderSettings settings = tracer.settings();
  settings.aov = true;
  tracer.setSettings(settings);
  EXPECT_FALSE(tracer.splitsShadows());
  EXPECT_EQ(tracer.passes(), before);
  session->render(1);
  settings.aov = false;
  tracer.setSettings(settings);
  EXPECT_TRUE(tracer.splitsShadows());
  EXPECT_EQ(tracer.passes(), before);
  session->render(2);
  EXPECT_EQ(tracer.readCounters().droppedSamples, 0u);
  expectNoValidationErrors(*session);
}
