// The hybrid modes' inspector: the recorded shadow and AO rays of a pixel are what its masks hold, the shadow
// ray's visibility is the geometry's, and the recorded reflection bounces add up to the reflection the pass
// wrote.
#include <gtest/gtest.h>

#include <cmath>

#include "gpu_fixture.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

TEST(HybridInspector, ShadowAndAoRaysAreWhatTheMasksHold) {
  ShadowScene s = makeShadowScene();
  render::SessionOptions o;
  o.sceneData = s.scene;
  o.settings.width = o.settings.height = 32;
  o.settings.envColor = glm::vec3(0.0f);
  o.mode = render::RenderMode::Hybrid;
  o.hybrid.aoRays = 6;
  o.hybrid.aoRadius = 3.0f;       // long enough to reach the floating box from the ground around it
  o.settings.sunAngleDeg = 0.0f;  // hard shadows: visibility is the geometry's
  o.hybrid.temporal = false;
  auto session = makeSession(o);
  auto* hybrid = session->hybrid();
  ASSERT_NE(hybrid, nullptr);
  size_t lit = 0, shadowed = 0, partlyOpen = 0;
  for (uint32_t y = 16; y < 32; y += 3) {
    for (uint32_t x = 1; x < 32; x += 4) {
      hybrid->setInspectPixel(glm::uvec2(x, y));
      session->render(1);
      const auto r = hybrid->readInspection();
      ASSERT_EQ(r.frameIndex, 0u);
      if (!r.covered) continue;
      const uint8_t shadowMask = hybrid->readShadowMask()[y * 32 + x];
      const uint8_t aoMask = hybrid->readAoMask()[y * 32 + x];
      EXPECT_EQ(r.shadowRay.visible ? 255 : 0, int(shadowMask)) << x << "," << y;
      EXPECT_EQ(r.shadow, r.shadowAverage);
      ASSERT_EQ(r.aoRays, 6u);
      float open = 0;
      for (uint32_t i = 0; i < r.aoRays; ++i) {
        open += r.aoRay[i].visible ? 1.0f : 0.0f;
        EXPECT_GT(glm::dot(r.aoRay[i].direction, r.normal), 0.0f) << "AO rays leave above the surface";
      }
      EXPECT_NEAR(aoMask / 255.0f, open / 6.0f, 1.0f / 255.0f) << x << "," << y;
      partlyOpen += open > 0 && open < 6;
      if (std::abs(r.position.y) > 1e-3f) continue;  // the box
      // On the ground: the shadow ray goes to the sun, and reaches it unless the box is in the way.
      EXPECT_NEAR(glm::dot(r.shadowRay.direction, -s.sunDirection), 1.0f, 1e-5f);
      const glm::vec3 p = r.position, d = -s.sunDirection;
      float t0 = 0.0f, t1 = 1e30f;
      for (int a = 0; a < 3; ++a) {
        float tn = (s.boxMin[a] - p[a]) / d[a], tf = (s.boxMax[a] - p[a]) / d[a];
        if (tn > tf) std::swap(tn, tf);
        t0 = std::max(t0, tn);
        t1 = std::min(t1, tf);
      }
      if (std::abs(t1 - t0) < 1e-3f) continue;  // grazing a box edge
      EXPECT_EQ(r.shadowRay.visible, t0 <= t1 ? 0u : 1u) << "at " << p.x << "," << p.z;
      (t0 <= t1 ? shadowed : lit)++;
    }
  }
  EXPECT_GT(lit, 10u);
  EXPECT_GT(shadowed, 0u);
  EXPECT_GT(partlyOpen, 0u) << "some AO ray should hit the box";
  expectNoValidationErrors(*session);
}

TEST(HybridInspector, ReflectionBouncesAddUpToTheReflection) {
  render::SessionOptions o;
  o.settings.width = o.settings.height = 32;
  o.mode = render::RenderMode::Reflections;
  o.hybrid.reflectionDepth = 3;
  o.quiet = true;
  auto session = makeSession(o);  // the default scene: the mirror sphere reflects the room
  auto* hybrid = session->hybrid();
  session->render(1);
  const auto reflection = hybrid->readReflection();
  size_t checked = 0, hits = 0;
  for (uint32_t i = 0; i < 32 * 32 && checked < 6; i += 7) {
    if (reflection[4 * i + 3] < 0.5f) continue;  // not traced there
    const uint32_t x = i % 32, y = i / 32;
    hybrid->setInspectPixel(glm::uvec2(x, y));
    session->render(1);
    const auto r = hybrid->readInspection();
    ASSERT_EQ(r.reflected, 1u) << x << "," << y;
    ASSERT_GE(r.reflectionBounces, 1u);
    glm::vec3 sum(0.0f);
    for (uint32_t b = 0; b < r.reflectionBounces; ++b) sum += r.bounces[b].added;
    for (int c = 0; c < 3; ++c) {
      const float image = reflection[4 * i + c];  // half float
      EXPECT_NEAR(r.reflection[c], image, 2e-3f * std::max(1.0f, image)) << x << "," << y;
      EXPECT_NEAR(sum[c], r.reflection[c], 1e-4f * std::max(1.0f, r.reflection[c])) << x << "," << y;
    }
    EXPECT_EQ(r.bounces[0].throughput, glm::vec3(1.0f));
    hits += r.bounces[0].hit;
    ++checked;
  }
  EXPECT_GE(checked, 3u) << "the mirror sphere should cover some pixels";
  EXPECT_GT(hits, 0u) << "the mirror sphere reflects the room";
  expectNoValidationErrors(*session);
}
