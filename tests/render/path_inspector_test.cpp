// The path inspector on the device: its records agree with the image the path tracer accumulates from the
// same samples, with themselves (throughput recomputed from the recorded factors), with what a white furnace
// and a sun-only scene must give, and the inspecting variant renders the same image as the normal one.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "render/path_inspector.h"
#include "shared/brdf.h"
#include "shared/sun.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

// Relative difference, with an absolute floor for values near zero.
void expectClose(const glm::vec3& a, const glm::vec3& b, float rel, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    const float tol = rel * std::max(1.0f, std::max(std::abs(a[c]), std::abs(b[c])));
    EXPECT_NEAR(a[c], b[c], tol) << what << " channel " << c;
  }
}

glm::vec4 pixelOf(const std::vector<float>& accum, uint32_t width, uint32_t x, uint32_t y) {
  const size_t i = (size_t(y) * width + x) * 4;
  return {accum[i], accum[i + 1], accum[i + 2], accum[i + 3]};
}

// The default scene at a small size: glossy and diffuse spheres, a room, an alpha-masked leaf, a sun.
render::SessionOptions defaultSceneOptions(uint32_t size = 24) {
  render::SessionOptions o;
  o.settings.width = size;
  o.settings.height = size;
  o.quiet = true;
  return o;
}

std::vector<render::InspectedSample> inspect(render::RenderSession& s, uint32_t x, uint32_t y, uint32_t n) {
  render::InspectRequest r;
  r.x = x;
  r.y = y;
  r.samples = n;
  s.pathTracer().setInspection(r);
  s.render(n);
  return render::inspectedSamples(s.pathTracer().readInspection());
}

}  // namespace

TEST(PathInspector, RecordsSumToThePixelTheTracerAccumulated) {
  auto session = makeSession(defaultSceneOptions());
  const uint32_t n = 6;
  size_t vertices = 0, lightSamples = 0;
  for (auto [x, y] : {std::pair{12u, 14u}, std::pair{5u, 20u}, std::pair{19u, 8u}}) {
    const auto samples = inspect(*session, x, y, n);
    ASSERT_EQ(samples.size(), n);
    const glm::vec4 pixel = pixelOf(session->pathTracer().readAccumulation(), 24, x, y);
    glm::dvec3 sum(0.0);
    uint32_t accumulated = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const auto& s = samples[i];
      EXPECT_EQ(s.record.sampleIndex, i);
      EXPECT_FALSE(s.truncated);
      ASSERT_TRUE(s.record.accumulated) << "the default scene gives finite samples";
      // The recorded terms add up to the value raygen accumulated for the sample...
      expectClose(s.sum, s.record.radiance, 1e-5f, "sample " + std::to_string(i));
      // ... and what raygen added at each vertex is what closest-hit recorded: emission and visible light
      // samples, times the throughput.
      for (const auto& v : s.vertices) {
        glm::vec3 reaching = v.record.emitted;
        for (const auto& l : v.lights)
          if (l.status == WB_INSPECT_NEE_TRACED && l.visible) reaching += l.contribution;
        expectClose(v.added, v.record.throughputIn * reaching, 1e-5f, "vertex added");
      }
      sum += glm::dvec3(s.sum);
      ++accumulated;
      vertices += s.vertices.size();
      for (const auto& v : s.vertices) lightSamples += v.lights.size();
    }
    // ... and their mean is the pixel's average.
    EXPECT_EQ(pixel.w, float(accumulated));
    expectClose(glm::vec3(sum / double(accumulated)), glm::vec3(pixel), 1e-5f,
                "pixel " + std::to_string(x) + "," + std::to_string(y));
    expectClose(glm::vec3(render::estimateOf(samples).mean()), glm::vec3(pixel), 1e-5f, "estimate");
  }
  EXPECT_GT(vertices, 3 * n) << "the pixels should see bounces";
  EXPECT_GT(lightSamples, 0u);
  expectNoValidationErrors(*session);
}

TEST(PathInspector, ThroughputFollowsFromTheRecordedFactors) {
  auto o = defaultSceneOptions();
  o.settings.rrStart =
      0;  // Russian roulette from the camera ray's hit on: its probability enters every vertex
  o.settings.maxBounces = 12;
  auto session = makeSession(o);
  size_t checked = 0, rrApplied = 0, specular = 0;
  for (auto [x, y] : {std::pair{12u, 14u}, std::pair{8u, 17u}, std::pair{16u, 16u}}) {
    for (const auto& s : inspect(*session, x, y, 8)) {
      for (size_t k = 0; k < s.vertices.size(); ++k) {
        const auto& v = s.vertices[k].record;
        const std::string at =
            "sample " + std::to_string(s.record.sampleIndex) + " vertex " + std::to_string(k);
        if (k == 0) expectClose(v.throughputIn, glm::vec3(1.0f), 0.0f, at + " camera throughput");
        if (k + 1 < s.vertices.size()) {
          // The next vertex starts with this one's throughput...
          EXPECT_EQ(s.vertices[k + 1].record.throughputIn, v.throughput) << at;
          // ... which is the previous throughput times f cos / pdf, over the survival probability.
          ASSERT_GT(v.pdf, 0.0f) << at;
          const glm::vec3 expected = v.throughputIn * v.brdf * v.cosine / v.pdf / v.rrProbability;
          expectClose(v.throughput, expected, 2e-4f, at);
          expectClose(v.weight, v.brdf * v.cosine / v.pdf, 2e-4f, at + " weight");
          EXPECT_GT(v.lobeProbability, 0.0f) << at;
          EXPECT_LE(v.lobeProbability, 1.0f) << at;
          checked++;
          rrApplied += v.rrOutcome == WB_INSPECT_RR_SURVIVED;
          specular += v.lobe == WB_LOBE_SPECULAR;
        } else if (s.record.end == WB_INSPECT_END_RUSSIAN_ROULETTE) {
          EXPECT_EQ(v.rrOutcome, uint32_t(WB_INSPECT_RR_TERMINATED)) << at;
          EXPECT_LT(v.rrProbability, 1.0f) << at;
        }
      }
    }
  }
  EXPECT_GT(checked, 20u);
  EXPECT_GT(rrApplied, 5u);
  EXPECT_GT(specular, 0u) << "some vertex should sample the glossy lobe";
  expectNoValidationErrors(*session);
}

// One bounce numbering (docs/path_inspector.md): bounce 0 is the camera ray's hit, and --rr-start N runs
// Russian roulette from bounce N on, so the first vertex whose record shows it is vertex N, never one before.
TEST(PathInspector, RussianRouletteFirstRunsAtTheVertexNumberedRrStart) {
  for (uint32_t rrStart : {1u, 3u}) {
    auto o = defaultSceneOptions();
    o.settings.rrStart = rrStart;
    o.settings.rrMin = o.settings.rrMax = 0.98f;  // a coin that rarely ends paths: most reach later vertices
    o.settings.maxBounces = 8;
    auto session = makeSession(o);
    size_t first = SIZE_MAX, atStart = 0;
    for (auto [x, y] : {std::pair{12u, 14u}, std::pair{8u, 17u}, std::pair{16u, 16u}}) {
      for (const auto& s : inspect(*session, x, y, 16)) {
        for (size_t k = 0; k < s.vertices.size(); ++k) {
          const auto& v = s.vertices[k].record;
          if (v.rrOutcome == WB_INSPECT_RR_NOT_APPLIED) continue;
          first = std::min(first, k);
          atStart += k == rrStart;
        }
      }
    }
    EXPECT_EQ(first, size_t(rrStart)) << "--rr-start " << rrStart;
    EXPECT_GT(atStart, 0u) << "--rr-start " << rrStart;
    expectNoValidationErrors(*session);
  }
}

TEST(PathInspector, WhiteFurnaceKeepsThroughputOne) {
  // A white Lambert sphere over a white Lambert floor in a uniform environment of 1: paths bounce between
  // them, every vertex samples the cosine lobe with f cos / pdf = 1, and without Russian roulette the
  // throughput stays 1 along the whole path.
  scene::Scene sc = makeFurnaceScene(lambert(glm::vec3(1.0f)));
  sc.meshes.push_back(quadMesh(20.0f, 0));
  glm::mat4 t(1.0f);
  t[3] = glm::vec4(0.0f, -1.0f, 0.0f, 1.0f);
  sc.instances.push_back({1, t, "floor"});
  sc.camera.eye = glm::vec3(0.0f, 0.5f, 3.0f);
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings.width = o.settings.height = 16;
  o.settings.envColor = glm::vec3(1.0f);
  o.settings.maxBounces = 16;
  o.settings.russianRoulette = false;
  auto session = makeSession(o);
  size_t multiBounce = 0, vertices = 0;
  for (auto [x, y] : {std::pair{8u, 6u}, std::pair{8u, 12u}, std::pair{3u, 14u}}) {
    const auto samples = inspect(*session, x, y, 8);
    ASSERT_EQ(samples.size(), 8u);
    for (const auto& s : samples) {
      multiBounce += s.vertices.size() > 1;
      for (const auto& iv : s.vertices) {
        const auto& v = iv.record;
        vertices++;
        EXPECT_EQ(v.lobe, uint32_t(WB_LOBE_DIFFUSE));
        EXPECT_EQ(v.lobeProbability, 1.0f);
        expectClose(v.weight, glm::vec3(1.0f), 1e-5f, "f cos / pdf");
        expectClose(v.throughputIn, glm::vec3(1.0f), 1e-5f, "throughput in");
        if (v.flags & WB_INSPECT_CONTINUED) expectClose(v.throughput, glm::vec3(1.0f), 1e-5f, "throughput");
        EXPECT_EQ(v.rrOutcome, uint32_t(WB_INSPECT_RR_NOT_APPLIED));
      }
      // Escaping rays see the environment at throughput 1: the sample is 1.
      if (s.record.escaped) expectClose(s.record.escapeThroughput, glm::vec3(1.0f), 1e-5f, "escape");
    }
    const glm::vec4 pixel = pixelOf(session->pathTracer().readAccumulation(), 16, x, y);
    EXPECT_NEAR(pixel.x, 1.0f, 0.25f) << "a furnace pixel averages 1";
  }
  EXPECT_GT(multiBounce, 5u) << "paths should bounce between sphere and floor";
  EXPECT_GT(vertices, 30u);
  expectNoValidationErrors(*session);
}

TEST(PathInspector, SunOnGroundIsPlainLightSamplingWithMisWeightOne) {
  ShadowScene s = makeShadowScene();
  render::SessionOptions o;
  o.sceneData = s.scene;
  o.settings.width = o.settings.height = 32;
  o.settings.envColor = glm::vec3(0.0f);
  auto session = makeSession(o);
  const float cosTheta = -s.sunDirection.y;
  const float expected = s.albedo / 3.14159265f * cosTheta * s.sunRadiance;
  size_t lit = 0, shadowed = 0;
  for (uint32_t y = 18; y < 32; y += 3) {
    for (uint32_t x = 2; x < 32; x += 5) {
      for (const auto& sample : inspect(*session, x, y, 2)) {
        if (sample.vertices.empty()) continue;
        const auto& v = sample.vertices[0];
        if (std::abs(v.record.position.y) > 1e-3f) continue;  // the box, not the ground
        ASSERT_GE(v.lights.size(), 1u);
        const auto& sun = v.lights[0];
        EXPECT_EQ(sun.kind, uint32_t(WB_INSPECT_LIGHT_DIRECTIONAL));
        EXPECT_EQ(sun.index, 0);
        EXPECT_EQ(sun.lightPdf, 0.0f) << "a delta light";
        EXPECT_EQ(sun.misWeight, 1.0f);
        EXPECT_EQ(sun.status, uint32_t(WB_INSPECT_NEE_TRACED));
        EXPECT_NEAR(sun.contribution.x, expected, 1e-4f * expected);
        // Visibility as the geometry says: is the box between the point and the sun?
        const glm::vec3 p = v.record.position, d = -s.sunDirection;
        float t0 = 0.0f, t1 = 1e30f;
        for (int a = 0; a < 3; ++a) {
          float tn = (s.boxMin[a] - p[a]) / d[a], tf = (s.boxMax[a] - p[a]) / d[a];
          if (tn > tf) std::swap(tn, tf);
          t0 = std::max(t0, tn);
          t1 = std::min(t1, tf);
        }
        const bool blocked = t0 <= t1;
        const float margin = std::abs(t1 - t0);  // rays grazing a box edge could go either way
        if (margin > 1e-3f) {
          EXPECT_EQ(sun.visible, blocked ? 0u : 1u) << "at " << p.x << "," << p.z;
        }
        (blocked ? shadowed : lit)++;
        const glm::vec3 added = v.added;
        if (!blocked && margin > 1e-3f) {
          EXPECT_NEAR(added.x, expected, 1e-4f * expected);
        }
      }
    }
  }
  EXPECT_GT(lit, 20u);
  EXPECT_GT(shadowed, 0u) << "the pixels should include the box's shadow";
  expectNoValidationErrors(*session);
}

// A sun of angular size (`--sun-angle`, 60 degrees across so that BRDF sampling meets its disc often): its
// light samples carry the cone's pdf and an MIS weight below one, escaping rays that meet the disc record its
// radiance with the complementary weight (escapeSun, in the escape's radiance), and every sample's records
// still add up to its value.
TEST(PathInspector, SunOfAngularSizeIsSampledWithMisAndMetByEscapingRays) {
  ShadowScene s = makeShadowScene();
  render::SessionOptions o;
  o.sceneData = s.scene;
  o.settings.width = o.settings.height = 24;
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.sunAngleDeg = 60.0f;
  auto session = makeSession(o);
  const float cosMax = std::cos(glm::radians(30.0f));
  const float disc = gpu::sunDiscRadiance(glm::vec3(s.sunRadiance), cosMax).x;
  size_t sunSamples = 0, discHits = 0;
  for (auto [x, y] : {std::pair{12u, 14u}, std::pair{5u, 20u}, std::pair{19u, 8u}}) {
    for (const auto& sample : inspect(*session, x, y, 16)) {
      const auto& r = sample.record;
      expectClose(sample.sum, r.radiance, 1e-5f, "sample " + std::to_string(r.sampleIndex));
      for (const auto& v : sample.vertices) {
        for (const auto& l : v.lights) {
          if (l.kind != WB_INSPECT_LIGHT_DIRECTIONAL) continue;
          EXPECT_NEAR(l.lightPdf, gpu::sunConePdf(cosMax), 1e-5f * gpu::sunConePdf(cosMax));
          if (l.status != WB_INSPECT_NEE_TRACED) continue;
          EXPECT_GT(l.misWeight, 0.0f);
          EXPECT_LT(l.misWeight, 1.0f);
          EXPECT_NEAR(l.radiance.x, disc, 1e-5f * disc);
          ++sunSamples;
        }
      }
      if (!r.escaped) continue;
      expectClose(r.escapeRadiance, r.escapeEnvironment * r.escapeMis + r.escapeSun, 1e-5f, "escape");
      if (r.escapeSun.x > 0.0f) {
        EXPECT_LT(r.escapeSun.x, disc) << "a BRDF-sampled ray: weighed against the cone sample";
        ++discHits;
      }
    }
  }
  EXPECT_GT(sunSamples, 20u);
  EXPECT_GT(discHits, 0u) << "some escaping ray should meet the disc";
  expectNoValidationErrors(*session);
}

TEST(PathInspector, InspectingVariantRendersTheSameImage) {
  auto session = makeSession(defaultSceneOptions(20));
  session->render(3);
  const auto normal = session->pathTracer().readAccumulation();
  const auto normalProgram = session->pathTracer().program();
  render::InspectRequest r;
  r.x = 10;
  r.y = 11;
  r.samples = 3;
  EXPECT_TRUE(session->pathTracer().setInspection(r));
  EXPECT_NE(session->pathTracer().program(), normalProgram);
  session->render(3);
  const auto inspected = session->pathTracer().readAccumulation();
  ASSERT_EQ(normal.size(), inspected.size());
  size_t differ = 0;
  for (size_t i = 0; i < normal.size(); ++i) {
    EXPECT_NEAR(normal[i], inspected[i], 1e-6f * std::max(1.0f, std::abs(normal[i]))) << "at " << i;
    differ += normal[i] != inspected[i];
  }
  EXPECT_EQ(render::inspectedSamples(session->pathTracer().readInspection()).size(), 3u);
  // Back to the normal variant: the same program as before, nothing recorded.
  EXPECT_TRUE(session->pathTracer().setInspection(std::nullopt));
  EXPECT_EQ(session->pathTracer().program(), normalProgram);
  RecordProperty("values_differing_in_the_last_bits", int(differ));
  expectNoValidationErrors(*session);
}

TEST(PathInspector, PixelTracedAloneGetsTheSameSamples) {
  auto session = makeSession(defaultSceneOptions());
  const auto full = inspect(*session, 7, 15, 4);
  const glm::vec4 fullPixel = pixelOf(session->pathTracer().readAccumulation(), 24, 7, 15);
  session->pathTracer().renderPixel(7, 15, 4);  // same request: the slots are rewritten
  const auto alone = render::inspectedSamples(session->pathTracer().readInspection());
  ASSERT_EQ(full.size(), alone.size());
  for (size_t i = 0; i < full.size(); ++i) {
    EXPECT_EQ(full[i].record.radiance, alone[i].record.radiance) << i;
    EXPECT_EQ(full[i].vertices.size(), alone[i].vertices.size()) << i;
  }
  EXPECT_EQ(pixelOf(session->pathTracer().readAccumulation(), 24, 7, 15), fullPixel);
  expectNoValidationErrors(*session);
}

TEST(PathInspector, NamesWhereAnInfiniteValueEnters) {
  // An environment of infinite radiance: a camera ray that misses the sphere adds it at its escape; one that
  // hits the sphere meets it first in the environment's light sample at the first vertex, unless that sample
  // fell below the surface (then at the escape of the continuation).
  render::SessionOptions o;
  o.sceneData = makeFurnaceScene(lambert(glm::vec3(0.5f)));
  o.settings.width = o.settings.height = 16;
  o.settings.envColor = glm::vec3(3.0e38f);
  o.settings.envIntensity = 10.0f;
  auto session = makeSession(o);
  size_t atEscape = 0, atLightSample = 0;
  for (auto [x, y] : {std::pair{0u, 0u}, std::pair{8u, 8u}}) {
    const auto samples = inspect(*session, x, y, 4);
    ASSERT_EQ(samples.size(), 4u);
    for (const auto& s : samples) {
      EXPECT_FALSE(s.record.accumulated) << "an infinite sample is dropped";
      ASSERT_TRUE(s.firstNonFinite.has_value());
      const bool lightTraced = !s.vertices.empty() && !s.vertices[0].lights.empty() &&
                               s.vertices[0].lights[0].status == WB_INSPECT_NEE_TRACED;
      if (lightTraced) {
        EXPECT_EQ(s.firstNonFinite->vertex, 0);
        EXPECT_EQ(s.firstNonFinite->term, uint32_t(WB_INSPECT_NAN_LIGHT));
        atLightSample++;
      } else {
        EXPECT_EQ(s.firstNonFinite->vertex, -1);
        EXPECT_EQ(s.firstNonFinite->term, uint32_t(WB_INSPECT_NAN_ENVIRONMENT));
        atEscape++;
      }
    }
    EXPECT_EQ(render::estimateOf(samples).dropped(), 4u);
    EXPECT_EQ(render::estimateOf(samples).count(), 0u);
  }
  EXPECT_GE(atEscape, 4u) << "pixel 0,0 sees past the sphere";
  EXPECT_GT(atLightSample, 0u) << "pixel 8,8 sees the sphere";
  expectNoValidationErrors(*session);
}

// Reflector guiding's coherent choices (pathtracer/guiding.glsl): two ground pixels of one aligned 8x4 tile,
// on the sunlit glossy scene, pick a reflector direction at their first hit in the same samples; with each
// pixel's own choice (WB_REFLECTOR_COHERENT=0) they pick it in different ones.
TEST(PathInspector, GuidedPixelsOfOneTileChooseTogether) {
  auto countMismatches = [](bool coherent) {
    auto o = defaultSceneOptions(32);
    o.scenePath = (wb::defaultScenePath().parent_path() / "sunlit_spheres.gltf").string();
    o.settings.envColor = glm::vec3(0.2f, 0.3f, 0.5f);
    o.settings.defines = {{"WB_REFLECTOR_GUIDING", "1"}, {"WB_REFLECTOR_COHERENT", coherent ? "1" : "0"}};
    auto session = makeSession(o);
    std::map<uint32_t, bool> guided[2];
    const uint32_t columns[2] = {8u, 15u};  // the first and last column of the tile x 8..15, rows 28..31
    for (int k = 0; k < 2; ++k) {
      for (const auto& s : inspect(*session, columns[k], 29, 64)) {
        if (s.vertices.empty()) continue;
        guided[k][s.record.sampleIndex] = s.vertices[0].record.lobe == WB_LOBE_REFLECTOR;
      }
    }
    expectNoValidationErrors(*session);
    size_t both = 0, mismatches = 0, reflector = 0;
    for (const auto& [sample, g] : guided[0]) {
      const auto other = guided[1].find(sample);
      if (other == guided[1].end()) continue;
      ++both;
      mismatches += g != other->second;
      reflector += g;
    }
    EXPECT_EQ(both, 64u) << "the inspector recorded both pixels' 64 samples";
    EXPECT_GT(reflector, 5u) << "the first hit (the ground) picks a reflector direction in ~30% of samples";
    return mismatches;
  };
  const size_t coherent = countMismatches(true), own = countMismatches(false);
  std::printf(" first-hit choices that differ between the tile's pixels: %zu of 64 coherent, %zu own\n",
              coherent, own);
  EXPECT_LE(coherent, 2u) << "one tile, one choice";
  EXPECT_GE(own, 10u) << "each pixel's own choice (~27 of 64 differ)";
}
