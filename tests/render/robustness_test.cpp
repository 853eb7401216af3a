// Robustness of the path tracer on the device, by numbers: hard cases never produce NaN/Inf, scale does not
// change the furnace (robust ray origins, no scene epsilon), alpha modes, and the AOVs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu_fixture.h"
#include "pt_helpers.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

// An equirectangular map of radiance 0.05 with one "sun" pixel 1e5 times brighter.
std::filesystem::path sunHdr() {
  const int w = 32, h = 16;
  std::vector<float> rgb(size_t(w) * h * 3, 0.05f);
  const size_t sun = (size_t(4) * w + 20) * 3;
  rgb[sun] = rgb[sun + 1] = rgb[sun + 2] = 5000.0f;
  return writeHdr("sun", w, h, rgb);
}

void renderHardCases(float scale) {
  const auto hdr = sunHdr();
  render::SessionOptions o;
  o.sceneData = scaledScene(makeHardCasesScene(), scale);
  o.settings.width = 48;
  o.settings.height = 48;
  o.settings.maxBounces = 6;
  o.settings.envPath = hdr.string();
  auto session = makeSession(o);
  std::filesystem::remove(hdr);
  render::RenderSettings variants[4] = {o.settings, o.settings, o.settings, o.settings};
  variants[1].nee = false;
  variants[2].mis = false;
  variants[3].sampler = render::SamplerKind::Pcg;
  variants[3].rrStart = 1;
  const char* names[4] = {"mis", "brdf only", "light only", "pcg rr1"};
  for (int v = 0; v < 4; ++v) {
    session->pathTracer().setSettings(variants[v]);
    session->render(8);
    const auto counters = session->pathTracer().readCounters();
    const auto stats = imageStats(session->image());
    std::printf("  scale %g %-10s: mean %.4f max %.3g, dropped %u, non-finite %zu, paths %u, rays %u\n",
                scale, names[v], (stats.mean[0] + stats.mean[1] + stats.mean[2]) / 3, stats.maxValue,
                counters.droppedSamples, stats.nonFinite, counters.pathCount, counters.rayCount);
    EXPECT_EQ(counters.droppedSamples, 0u) << names[v];
    EXPECT_EQ(stats.nonFinite, 0u) << names[v];
    EXPECT_GT(stats.mean[0] + stats.mean[1] + stats.mean[2], 0.01)
        << names[v] << ": image should not be black";
    // The albedo AOV's alpha holds the dropped fraction; the info AOV the path length: both finite.
  }
  expectNoValidationErrors(*session);
}

double furnace(float scale, glm::vec3 offset = glm::vec3(0.0f)) {
  render::SessionOptions o;
  scene::Scene sc = scaledScene(makeFurnaceScene(lambert(glm::vec3(1.0f))), scale);
  sc.instances[0].transform[3] += glm::vec4(offset, 0.0f);
  sc.camera.eye += offset;
  sc.camera.target += offset;
  o.sceneData = sc;
  o.settings.width = 32;
  o.settings.height = 32;
  o.settings.envColor = glm::vec3(1.0f);
  o.settings.maxBounces = 64;
  auto session = makeSession(o);
  session->render(64);
  const auto img = session->image();
  const auto stats = imageStats(img);
  EXPECT_EQ(stats.nonFinite, 0u);
  EXPECT_EQ(session->pathTracer().readCounters().droppedSamples, 0u);
  float lo = 1e30f, hi = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    lo = std::min(lo, img.pixels[i]);
    hi = std::max(hi, img.pixels[i]);
  }
  const double mean = imageMean(img);
  std::printf("  furnace at scale %g offset %g: mean %.5f, pixels in [%.4f, %.4f]\n", scale, offset.x, mean,
              lo, hi);
  EXPECT_GT(lo, 0.85f) << "a pixel lost energy: self-intersection of shadow or bounce rays";
  expectNoValidationErrors(*session);
  return mean;
}

}  // namespace

TEST(HardCases, NoNanOrInfAtUnitScale) {
  renderHardCases(1.0f);
}
TEST(HardCases, NoNanOrInfAtMillimetreScale) {
  renderHardCases(1e-3f);
}
TEST(HardCases, NoNanOrInfAt1e5Scale) {
  renderHardCases(1e5f);
}

TEST(SelfIntersection, FurnaceIsOneAtAnyScale) {
  EXPECT_NEAR(furnace(1e-3f), 1.0, 0.005);
  EXPECT_NEAR(furnace(1e5f), 1.0, 0.005);
  // Far from the origin too: a unit sphere 1e4 units away (float spacing there ~1e-3).
  EXPECT_NEAR(furnace(1.0f, glm::vec3(1e4f, 0.0f, 0.0f)), 1.0, 0.005);
}

// Four quads in front of an emissive background (radiance 1), black environment, black foreground materials:
// MASK with alpha 0.2 < cutoff is invisible (pixels exactly 1), MASK with alpha 0.8 is solid (0), BLEND with
// alpha 0.5 covers half (0.5 on average), OPAQUE with alpha 0 is solid (0: opaque geometry ignores alpha).
TEST(Alpha, MaskBlendAndOpaque) {
  scene::Scene sc;
  sc.sourcePath = "alpha-test";
  gpu::Material bg = lambert(glm::vec3(0.0f));
  bg.emissive = glm::vec3(1.0f);
  gpu::Material maskLow = lambert(glm::vec3(0.0f)), maskHigh = maskLow, blend = maskLow, opaque = maskLow;
  maskLow.alphaMode = maskHigh.alphaMode = WB_ALPHA_MASK;
  maskLow.baseColorFactor.a = 0.2f;
  maskHigh.baseColorFactor.a = 0.8f;
  blend.alphaMode = WB_ALPHA_BLEND;
  blend.baseColorFactor.a = 0.5f;
  opaque.baseColorFactor.a = 0.0f;
  sc.materials = {bg, maskLow, maskHigh, blend, opaque};
  sc.materialNames = {"emissive", "mask-0.2", "mask-0.8", "blend-0.5", "opaque-alpha-0"};
  sc.meshes = {quadMesh(20.0f, 0)};
  for (int m = 1; m <= 4; ++m) sc.meshes.push_back(quadMesh(0.8f, m));
  sc.instances.push_back({0, glm::mat4(1.0f), "background"});
  const float xs[4] = {-3.0f, -1.0f, 1.0f, 3.0f};
  for (int q = 0; q < 4; ++q) {
    glm::mat4 t(1.0f);
    t[3] = glm::vec4(xs[q], 1.0f, 0.0f, 1.0f);
    sc.instances.push_back({1 + q, t, sc.materialNames[1 + q]});
  }
  sc.camera.eye = glm::vec3(0.0f, 10.0f, 0.0f);
  sc.camera.target = glm::vec3(0.0f);
  sc.camera.up = glm::vec3(0, 0, -1);
  sc.camera.yfov = 0.9f;
  sc.bounds = {glm::vec3(-20, 0, -20), glm::vec3(20, 1, 20)};

  render::SessionOptions o;
  o.sceneData = sc;
  o.settings.width = 96;
  o.settings.height = 48;
  o.settings.envColor = glm::vec3(0.0f);
  auto session = makeSession(o);
  session->render(16);
  const auto img = session->image();
  EXPECT_EQ(session->pathTracer().readCounters().droppedSamples, 0u);

  // Classify pixels by where the rays through their corners and centre meet the plane y = 1.
  const auto& cam = session->sceneCamera();
  glm::mat4 proj = glm::perspective(cam.yfov, float(img.width) / float(img.height), cam.znear, 1000.0f);
  proj[1][1] *= -1.0f;
  const glm::mat4 projInv = glm::inverse(proj), viewInv = glm::inverse(cam.view);
  auto quadAt = [&](float px, float py) {
    const glm::vec2 ndc(px / img.width * 2.0f - 1.0f, py / img.height * 2.0f - 1.0f);
    const glm::vec4 target = projInv * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 o = glm::vec3(viewInv * glm::vec4(0, 0, 0, 1));
    const glm::vec3 d = glm::vec3(viewInv * glm::vec4(glm::normalize(glm::vec3(target) / target.w), 0.0f));
    const glm::vec3 p = o + d * ((1.0f - o.y) / d.y);
    for (int q = 0; q < 4; ++q) {
      if (std::abs(p.x - xs[q]) < 0.8f && std::abs(p.z) < 0.8f) return q;
    }
    return -1;
  };
  double sum[5] = {0, 0, 0, 0, 0}, minV[5], maxV[5];
  int count[5] = {0, 0, 0, 0, 0};
  for (int c = 0; c < 5; ++c) {
    minV[c] = 1e30;
    maxV[c] = -1e30;
  }
  for (uint32_t y = 0; y < img.height; ++y) {
    for (uint32_t x = 0; x < img.width; ++x) {
      const int c = quadAt(x + 0.5f, y + 0.5f);
      bool uniform = true;
      for (float dy : {0.0f, 1.0f}) {
        for (float dx : {0.0f, 1.0f}) uniform = uniform && quadAt(x + dx, y + dy) == c;
      }
      if (!uniform) continue;
      const double v = img.at(x, y, 1);
      const int k = c + 1;  // 0 = background
      sum[k] += v;
      count[k]++;
      minV[k] = std::min(minV[k], v);
      maxV[k] = std::max(maxV[k], v);
    }
  }
  const char* names[5] = {"background", "mask 0.2", "mask 0.8", "blend 0.5", "opaque alpha 0"};
  for (int k = 0; k < 5; ++k) {
    std::printf("  %-15s %4d px: mean %.4f, range [%.4f, %.4f]\n", names[k], count[k], sum[k] / count[k],
                minV[k], maxV[k]);
    ASSERT_GT(count[k], 40) << names[k] << ": the test should see the quad";
  }
  EXPECT_NEAR(minV[0], 1.0, 1e-5);  // emissive background seen directly
  EXPECT_NEAR(maxV[0], 1.0, 1e-5);
  EXPECT_NEAR(minV[1], 1.0, 1e-5) << "MASK below the cutoff must be invisible";
  EXPECT_NEAR(maxV[1], 1.0, 1e-5);
  EXPECT_LT(maxV[2], 1e-6) << "MASK above the cutoff must be solid";
  // BLEND: each sample passes with probability 0.5; 16 spp over >= 40 pixels: sigma of the mean <= 0.02.
  EXPECT_NEAR(sum[3] / count[3], 0.5, 0.06) << "BLEND alpha 0.5 should cover half";
  EXPECT_GT(maxV[3] - minV[3], 0.1) << "stochastic transparency varies per pixel";
  EXPECT_LT(maxV[4], 1e-6) << "OPAQUE ignores alpha (no any-hit on opaque geometry)";
  expectNoValidationErrors(*session);
}

// The first-hit AOVs of a uniform Lambert plane: albedo = its base colour, normal = its normal, distance > 0.
TEST(Aov, AlbedoAndNormalOfALambertPlane) {
  const glm::vec3 color(0.2f, 0.5f, 0.7f);
  scene::Scene sc;
  sc.sourcePath = "aov-test";
  sc.materials = {lambert(color)};
  sc.materialNames = {"plane"};
  sc.meshes = {quadMesh(100.0f, 0)};
  sc.instances.push_back({0, glm::mat4(1.0f), "plane"});
  sc.camera.eye = glm::vec3(0.0f, 5.0f, 1.0f);
  sc.camera.target = glm::vec3(0.0f);
  sc.camera.up = glm::vec3(0, 1, 0);
  sc.camera.yfov = 0.8f;
  sc.bounds = {glm::vec3(-100, 0, -100), glm::vec3(100, 0, 100)};
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings.width = 32;
  o.settings.height = 32;
  o.settings.aov = true;
  auto session = makeSession(o);
  session->render(4);
  const auto albedo = session->aov(render::Aov::Albedo);
  const auto normal = session->aov(render::Aov::Normal);
  double maxAlbedoErr = 0, maxNormalErr = 0, minDist = 1e30, maxDist = 0;
  for (uint32_t y = 0; y < albedo.height; ++y) {
    for (uint32_t x = 0; x < albedo.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        maxAlbedoErr = std::max(maxAlbedoErr, double(std::abs(albedo.at(x, y, c) - color[c])));
        maxNormalErr = std::max(maxNormalErr, double(std::abs(normal.at(x, y, c) - (c == 1 ? 1.0f : 0.0f))));
      }
      EXPECT_EQ(albedo.at(x, y, 3), 0.0f) << "dropped-sample fraction";
      minDist = std::min(minDist, double(normal.at(x, y, 3)));
      maxDist = std::max(maxDist, double(normal.at(x, y, 3)));
    }
  }
  std::printf("  albedo max error %.2e, normal max error %.2e, first-hit distance in [%.3f, %.3f]\n",
              maxAlbedoErr, maxNormalErr, minDist, maxDist);
  EXPECT_LT(maxAlbedoErr, 1e-3);  // half-float storage
  EXPECT_LT(maxNormalErr, 1e-3);
  EXPECT_GT(minDist, 4.9);  // the plane is at least the camera height (5) away
  EXPECT_LT(maxDist, 20.0);
  expectNoValidationErrors(*session);
}

// The drop path itself: a sample that is Inf or NaN is counted and never accumulated. An emitter of infinite
// (then NaN) radiance fills the view: every sample is dropped, the image stays finite (black), and the
// albedo AOV's alpha reports a dropped fraction of 1 (the "NaN/Inf dropped" debug view).
TEST(NonFiniteSamples, AreCountedAndNeverAccumulated) {
  for (const float bad : {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
    SCOPED_TRACE(std::isnan(bad) ? "NaN" : "Inf");
    scene::Scene sc;
    sc.sourcePath = "non-finite-emitter";
    gpu::Material m = lambert(glm::vec3(0.5f));
    sc.materials = {m};
    sc.materialNames = {"bad-emitter"};
    sc.meshes = {quadMesh(100.0f, 0)};
    sc.instances.push_back({0, glm::mat4(1.0f), "plane"});
    sc.camera.eye = glm::vec3(0.0f, 2.0f, 0.5f);
    sc.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    sc.camera.yfov = 0.5f;
    sc.bounds = {glm::vec3(-100, 0, -100), glm::vec3(100, 0.1f, 100)};
    render::SessionOptions o;
    o.sceneData = sc;
    o.settings.width = 16;
    o.settings.height = 16;
    o.settings.aov = true;
    o.settings.generic = true;  // every feature compiled in: the emission is read whatever its value
    auto session = makeSession(o);
    // The host refuses non-finite emission when it builds the light tables, so the bad value arrives the
    // way a live edit does: straight into the material buffer.
    m.emissive = glm::vec3(bad, 0.0f, 0.0f);
    session->gpuScene().updateMaterials({m});
    session->render(4);
    const auto counters = session->pathTracer().readCounters();
    EXPECT_EQ(counters.droppedSamples, 16u * 16u * 4u) << "every sample sees the emitter";
    const auto stats = imageStats(session->image());
    EXPECT_EQ(stats.nonFinite, 0u);
    EXPECT_EQ(stats.maxValue, 0.0f) << "nothing was accumulated";
    const auto albedo = session->aov(render::Aov::Albedo);
    for (size_t i = 3; i < albedo.pixels.size(); i += 4) ASSERT_NEAR(albedo.pixels[i], 1.0f, 1e-3f) << i / 4;
    expectNoValidationErrors(*session);
  }
}
