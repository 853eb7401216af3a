// The bare-ray roofline (render/roofline.h) traces the path tracer's own scene: its camera rays land where
// the geometry is, its shadow rays find the shadow the scene's box casts (checked against a ray-box test on
// the host), its bounce rays hit and escape, and the rays each launch counts are the rays it traces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gpu_fixture.h"
#include "render/roofline.h"
#include "test_scenes.h"

using namespace wb;

namespace {

// Whether the ray o + t d (t > 0) meets the box (slab test).
bool hitsBox(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
  float t0 = 0.0f, t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / d[a];
    float tn = (lo[a] - o[a]) * inv, tf = (hi[a] - o[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  return t0 <= t1;
}

}  // namespace

TEST(Roofline, TracesThePathTracersSceneAndCountsItsRays) {
  const auto ss = wb::testing::makeShadowScene();
  render::SessionOptions o;
  o.sceneData = ss.scene;
  o.settings.width = o.settings.height = 48;
  o.settings.envColor = glm::vec3(0.0f);
  auto s = wb::testing::makeSession(o);
  render::Roofline roofline({s->context(), s->library(), s->scene(), s->gpuScene(), s->environment()}, 48, 48,
                            s->camera(), o.settings.maxBounces);
  const uint64_t pixels = 48 * 48;
  // The camera looks down at the plane: every camera ray hits the plane or the box.
  EXPECT_EQ(roofline.hits(), pixels);
  EXPECT_EQ(roofline.raysPerLaunch(render::BareRays::Primary), pixels);
  EXPECT_EQ(roofline.raysPerLaunch(render::BareRays::Diffuse), pixels + roofline.hits());
  EXPECT_EQ(roofline.raysPerLaunch(render::BareRays::Shadow), roofline.litHits());
  EXPECT_GT(roofline.litHits(), pixels / 2);  // the plane faces the sun, and the box's top

  const auto hits = roofline.readHits();
  uint32_t onPlane = 0;
  for (size_t i = 0; i < hits.size(); i += 4) {
    const glm::vec3 p(hits[i], hits[i + 1], hits[i + 2]);
    const bool plane = std::abs(p.y) < 1e-3f;
    const bool box =
        glm::all(glm::greaterThan(p, ss.boxMin - 1e-3f)) && glm::all(glm::lessThan(p, ss.boxMax + 1e-3f));
    EXPECT_TRUE(plane || box) << "pixel " << i / 4 << " hit (" << p.x << ", " << p.y << ", " << p.z << ")";
    onPlane += plane ? 1 : 0;
  }

  // Shadow rays from the plane: occluded exactly where a ray towards the sun meets the box.
  s->context().submitAndWait([&](VkCommandBuffer cmd) { roofline.record(cmd, render::BareRays::Shadow, 1); });
  const auto visible = roofline.readResult();
  const glm::vec3 toLight = -ss.sunDirection;
  uint32_t shadowed = 0, disagree = 0;
  for (size_t i = 0; i < hits.size(); i += 4) {
    const glm::vec3 p(hits[i], hits[i + 1], hits[i + 2]);
    if (std::abs(p.y) >= 1e-3f) continue;
    const bool expectedVisible = !hitsBox(p, toLight, ss.boxMin, ss.boxMax);
    shadowed += expectedVisible ? 0 : 1;
    disagree += (visible[i] > 0.5f) != expectedVisible ? 1 : 0;
  }
  EXPECT_GT(shadowed, 20u) << "the box's shadow is in view";
  EXPECT_LE(disagree, onPlane / 100) << "shadowed " << shadowed << " of " << onPlane;

  // Bounce rays from the plane: some reach the box above it, most escape.
  s->context().submitAndWait(
      [&](VkCommandBuffer cmd) { roofline.record(cmd, render::BareRays::Diffuse, 1); });
  const auto bounce = roofline.readResult();
  uint32_t hitBox = 0, escaped = 0;
  for (size_t i = 0; i < bounce.size(); i += 4) (bounce[i] > 0.0f ? hitBox : escaped) += 1;
  EXPECT_GT(hitBox, 0u);
  EXPECT_GT(escaped, hitBox);
  wb::testing::expectNoValidationErrors(*s);
}

// Bare paths of one bounce trace exactly, per pixel, the camera ray, a shadow ray where its hit faces the sun
// and the bounce: pixels + lit hits + hits. With no bounce, the camera rays alone. Longer walks trace more,
// and a walk's shadow rays reach the light only from where the sun is visible.
TEST(Roofline, BarePathsTraceThePathTracersMixOfRays) {
  const auto ss = wb::testing::makeShadowScene();
  render::SessionOptions o;
  o.sceneData = ss.scene;
  o.settings.width = o.settings.height = 48;
  o.settings.envColor = glm::vec3(0.0f);
  auto s = wb::testing::makeSession(o);
  const render::RendererResources r{s->context(), s->library(), s->scene(), s->gpuScene(), s->environment()};
  const uint64_t pixels = 48 * 48;
  render::Roofline none(r, 48, 48, s->camera(), 0), one(r, 48, 48, s->camera(), 1),
      eight(r, 48, 48, s->camera(), 8);
  EXPECT_EQ(none.raysPerLaunch(render::BareRays::Path), pixels);
  EXPECT_EQ(one.raysPerLaunch(render::BareRays::Path), pixels + one.litHits() + one.hits());
  EXPECT_GE(eight.raysPerLaunch(render::BareRays::Path), one.raysPerLaunch(render::BareRays::Path));
  EXPECT_LE(eight.raysPerLaunch(render::BareRays::Path), pixels * (1 + 2 * 8));

  // One bounce: the shadow rays that reach the sun are those the Shadow kind finds visible.
  s->context().submitAndWait([&](VkCommandBuffer cmd) { one.record(cmd, render::BareRays::Shadow, 1); });
  const auto visible = one.readResult();
  s->context().submitAndWait([&](VkCommandBuffer cmd) { one.record(cmd, render::BareRays::Path, 1); });
  const auto walks = one.readResult();
  uint32_t disagree = 0;
  for (size_t i = 0; i < walks.size(); i += 4)
    disagree += (walks[i + 1] > 0.5f) != (visible[i] > 0.5f) ? 1 : 0;
  EXPECT_EQ(disagree, 0u);
  EXPECT_EQ(s->context().validationErrors(), 0u);
}
