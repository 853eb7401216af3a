// Unbiasedness of the path tracer's estimators, by numbers: different strategies (light sampling only, BRDF
// sampling only, MIS; Russian roulette on/off/aggressive) must agree in mean within 3 sigma, sigma from the
// per-pixel variance of independent batches (see estimateMean). Also environment rotation and intensity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "common/paths.h"
#include "stb_image.h"
#include "gpu_fixture.h"
#include "pt_helpers.h"
#include "shared/spherical_triangle.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

std::string gardenPath() {
  return (sharedDir() / "assets/env/chinese_garden_1k.hdr").string();
}

// The garden map with every channel clamped to maxValue, as a temp .hdr. The original has a sun of luminance
// ~68000 covering ~10 pixels (~4e-4 sr) that holds ~69% of the map's (sin-weighted) energy: BRDF sampling
// alone hits it about once per 10^4 samples, so at test sample counts its estimate is dominated by whether
// the sun happened to be hit (a heavy tail the sample variance cannot see). Clamped at 100 the map keeps its
// structure and a large dynamic range (mean ~0.3) but BRDF-only sampling converges in test time.
std::filesystem::path clampedGarden(float maxValue) {
  int w = 0, h = 0, c = 0;
  float* data = stbi_loadf(gardenPath().c_str(), &w, &h, &c, 3);
  if (!data) throw std::runtime_error("cannot read " + gardenPath());
  std::vector<float> rgb(data, data + size_t(w) * h * 3);
  stbi_image_free(data);
  for (float& v : rgb) v = std::min(v, maxValue);
  return writeHdr("garden_clamped", w, h, rgb);
}

render::RenderSettings envSettings() {
  render::RenderSettings s;
  s.width = 32;
  s.height = 32;
  s.maxBounces = 4;
  s.envPath = gardenPath();
  return s;
}

void expectAgree(const char* what, const Estimate& a, const char* whatB, const Estimate& b) {
  const double sigma = std::sqrt(a.sigma * a.sigma + b.sigma * b.sigma);
  std::printf("  %-22s %.5f +- %.5f  vs  %-22s %.5f +- %.5f  -> %.2f sigma\n", what, a.mean, a.sigma, whatB,
              b.mean, b.sigma, std::abs(a.mean - b.mean) / sigma);
  EXPECT_LT(std::abs(a.mean - b.mean), 3.0 * sigma) << what << " vs " << whatB;
}

void expectClean(const char* what, const Estimate& e) {
  EXPECT_EQ(e.dropped, 0u) << what;
  EXPECT_EQ(e.nonFinite, 0u) << what;
  // The comparison must have power: a relative error bar of a few percent at most.
  EXPECT_LT(e.sigma, 0.03 * e.mean) << what << ": too noisy for the comparison to mean anything";
}

}  // namespace

// The garden map lights a glossy metal and a rough dielectric sphere on a floor. Light sampling only (the
// environment reached through NEE alone), BRDF sampling only (no NEE) and MIS estimate the same integral.
// Three-way on the clamped map (see clampedGarden); MIS against light-only also on the original map with its
// sun.
TEST(Unbiased, MisLightOnlyAndBrdfOnlyAgree) {
  const auto clamped = clampedGarden(100.0f);
  render::SessionOptions o;
  o.sceneData = makeEnvSpheresScene();
  o.settings = envSettings();
  o.settings.envPath = clamped.string();
  auto session = makeSession(o);
  std::filesystem::remove(clamped);
  render::RenderSettings mis = o.settings, lightOnly = o.settings, brdfOnly = o.settings;
  lightOnly.mis = false;
  brdfOnly.nee = false;
  const Estimate eMis = estimateMean(*session, mis, 16, 32, 100);
  const Estimate eLight = estimateMean(*session, lightOnly, 16, 32, 200);
  const Estimate eBrdf = estimateMean(*session, brdfOnly, 16, 32, 300);
  expectClean("mis", eMis);
  expectClean("light only", eLight);
  expectClean("brdf only", eBrdf);
  std::printf(" clamped garden map:\n");
  expectAgree("mis", eMis, "light only", eLight);
  expectAgree("mis", eMis, "brdf only", eBrdf);
  expectAgree("light only", eLight, "brdf only", eBrdf);
  // The default sampler (Sobol + blue noise) converges to the same value.
  session->pathTracer().setSettings(mis);
  session->render(128);
  const Estimate eSobol{imageMean(session->image()), 0.0, session->pathTracer().readCounters().droppedSamples,
                        0};
  expectAgree("sobol mis (128 spp)", eSobol, "pcg mis", eMis);
  EXPECT_EQ(eSobol.dropped, 0u);
  expectNoValidationErrors(*session);
}

TEST(Unbiased, MisAndLightOnlyAgreeWithTheSun) {
  render::SessionOptions o;
  o.sceneData = makeEnvSpheresScene();
  o.settings = envSettings();
  auto session = makeSession(o);
  render::RenderSettings mis = o.settings, lightOnly = o.settings;
  lightOnly.mis = false;
  const Estimate eMis = estimateMean(*session, mis, 16, 16, 700);
  const Estimate eLight = estimateMean(*session, lightOnly, 16, 16, 800);
  expectClean("mis", eMis);
  expectClean("light only", eLight);
  std::printf(" original garden map (sun ~68000):\n");
  expectAgree("mis", eMis, "light only", eLight);
  expectNoValidationErrors(*session);
}

// Continuation rays towards glossy reflectors (pathtracer/guiding.glsl): the sun focused by a smooth metal
// sphere onto the floor. The mixture's pdf weighs every estimate that weighs against BRDF sampling, so guided
// MIS, guided BRDF sampling alone (no next-event estimation: the sun, here of angular size, is reached
// through the miss shader), guided MIS with each pixel's own choice (not its tile's) and unguided MIS must
// agree.
TEST(Unbiased, ReflectorGuidingAgreesWithBrdfSampling) {
  render::SessionOptions o;
  o.sceneData = makeEnvSpheresScene();
  gpu::DirectionalLight sun{};
  sun.direction = glm::normalize(glm::vec3(0.6f, -0.7f, -0.3f));
  sun.cosAngularRadius = std::cos(glm::radians(6.0f));
  sun.radiance = glm::vec3(40.0f);
  o.sceneData->lights.push_back(sun);
  o.settings = envSettings();
  o.settings.envPath.clear();
  o.settings.envColor = glm::vec3(0.2f, 0.3f, 0.5f);
  render::SessionOptions offOptions = o, ownOptions = o;
  o.settings.defines = {{"WB_REFLECTOR_GUIDING", "1"}};
  offOptions.settings.defines = {{"WB_REFLECTOR_GUIDING", "0"}};
  ownOptions.settings.defines = {{"WB_REFLECTOR_GUIDING", "1"}, {"WB_REFLECTOR_COHERENT", "0"}};
  auto session = makeSession(o);
  auto offSession = makeSession(offOptions);
  auto ownSession = makeSession(ownOptions);
  render::RenderSettings mis = o.settings, brdfOnly = o.settings;
  brdfOnly.nee = false;
  const Estimate eMis = estimateMean(*session, mis, 16, 16, 100);
  const Estimate eBrdf = estimateMean(*session, brdfOnly, 16, 64, 300);
  const Estimate eOff = estimateMean(*offSession, offOptions.settings, 16, 16, 400);
  const Estimate eOwn = estimateMean(*ownSession, ownOptions.settings, 16, 16, 500);
  expectClean("guided mis", eMis);
  expectClean("guided brdf only", eBrdf);
  expectClean("unguided mis", eOff);
  expectClean("guided mis, own", eOwn);
  std::printf(" sun and a glossy metal sphere:\n");
  expectAgree("guided mis", eMis, "guided brdf only", eBrdf);
  expectAgree("guided mis", eMis, "unguided mis", eOff);
  expectAgree("guided brdf only", eBrdf, "unguided mis", eOff);
  expectAgree("guided mis, own", eOwn, "unguided mis", eOff);
  expectAgree("guided mis, own", eOwn, "guided mis", eMis);
  expectNoValidationErrors(*session);
  expectNoValidationErrors(*offSession);
  expectNoValidationErrors(*ownSession);
}

// Russian roulette only reweights surviving paths: on, off, from the first bounce with a tight survival clamp
// (every path survives with probability 0.3 exactly), and with survival proportional to the throughput
// (exponent 1) or its square root (0.5) estimate the same image.
TEST(Unbiased, RussianRouletteOnOffAndAggressiveAgree) {
  render::SessionOptions o;
  o.sceneData = makeEnvSpheresScene();
  o.settings = envSettings();
  o.settings.maxBounces = 6;
  auto session = makeSession(o);
  render::RenderSettings on = o.settings, off = o.settings, aggressive = o.settings, linear = o.settings,
                         root = o.settings;
  off.russianRoulette = false;
  aggressive.rrStart = 1;
  aggressive.rrMin = 0.3f;
  aggressive.rrMax = 0.3f;
  linear.rrStart = 1;
  linear.rrExponent = 1.0f;
  root.rrStart = 1;
  root.rrExponent = 0.5f;
  const Estimate eOn = estimateMean(*session, on, 16, 16, 400);
  const Estimate eOff = estimateMean(*session, off, 16, 16, 500);
  const Estimate eAggr = estimateMean(*session, aggressive, 16, 16, 600);
  const Estimate eLinear = estimateMean(*session, linear, 16, 16, 700);
  const Estimate eRoot = estimateMean(*session, root, 16, 16, 800, render::SamplerKind::Owen);
  expectClean("rr on", eOn);
  expectClean("rr off", eOff);
  expectClean("rr start 1 clamp 0.3", eAggr);
  expectClean("rr exponent 1", eLinear);
  expectClean("rr exponent 0.5 (owen)", eRoot);
  expectAgree("rr on", eOn, "rr off", eOff);
  expectAgree("rr start 1 clamp 0.3", eAggr, "rr off", eOff);
  expectAgree("rr start 1 clamp 0.3", eAggr, "rr on", eOn);
  expectAgree("rr exponent 1", eLinear, "rr off", eOff);
  expectAgree("rr exponent 0.5 (owen)", eRoot, "rr off", eOff);
  expectNoValidationErrors(*session);
}

// A large emitter 0.25 above a floor: from the floor it subtends a large solid angle (sampled by solid angle,
// shared/spherical_triangle.h) and BRDF sampling hits it often, so MIS weighs both strategies heavily. Direct
// light only (one bounce): MIS, light sampling alone and BRDF sampling alone must agree. If the pdf MIS
// evaluates for a BRDF sample that hits the emitter were not the pdf next-event estimation sampled with (e.g.
// the area pdf there), the weights would not sum to one and MIS would be off by several sigma.
TEST(Emitters, SolidAngleSamplingKeepsMisConsistent) {
  scene::Scene sc = makeShadowScene().scene;
  sc.lights.clear();
  sc.meshes.resize(1);
  sc.instances.resize(1);
  gpu::Material emitter = lambert(glm::vec3(0.0f));
  emitter.emissive = glm::vec3(2.0f);
  sc.materials.push_back(emitter);
  sc.meshes.push_back(quadMesh(1.0f, int(sc.materials.size() - 1)));
  glm::mat4 t(1.0f);
  t[1][1] = -1.0f, t[2][2] = -1.0f;  // facing the floor
  t[3] = glm::vec4(0.3f, 0.25f, 0.0f, 1.0f);
  sc.instances.push_back({1, t, "emitter"});
  sc.camera.eye = glm::vec3(0.0f, 2.0f, 3.0f);
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings.width = 24;
  o.settings.height = 24;
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.maxBounces = 1;
  auto session = makeSession(o);
  render::RenderSettings mis = o.settings, lightOnly = o.settings, brdfOnly = o.settings;
  lightOnly.mis = false;
  brdfOnly.nee = false;
  for (auto sampler : {render::SamplerKind::Pcg, render::SamplerKind::Owen}) {
    const Estimate eMis = estimateMean(*session, mis, 12, 16, 100, sampler);
    const Estimate eLight = estimateMean(*session, lightOnly, 12, 16, 200, sampler);
    const Estimate eBrdf = estimateMean(*session, brdfOnly, 12, 64, 300, sampler);
    for (const Estimate* e : {&eMis, &eLight, &eBrdf}) {
      EXPECT_EQ(e->nonFinite, 0u);
      EXPECT_EQ(e->dropped, 0u);
      EXPECT_LT(e->sigma, 0.01 * e->mean) << "too noisy to compare";
    }
    auto z = [](const Estimate& a, const Estimate& b) {
      return std::abs(a.mean - b.mean) / std::sqrt(a.sigma * a.sigma + b.sigma * b.sigma);
    };
    std::printf("%s: mis %.5f +- %.5f, light only %.5f +- %.5f, brdf only %.5f +- %.5f\n",
                render::samplerName(sampler), eMis.mean, eMis.sigma, eLight.mean, eLight.sigma, eBrdf.mean,
                eBrdf.sigma);
    EXPECT_LT(z(eMis, eLight), 4.0) << render::samplerName(sampler);
    EXPECT_LT(z(eMis, eBrdf), 4.0) << render::samplerName(sampler);
    EXPECT_LT(z(eLight, eBrdf), 4.0) << render::samplerName(sampler);
  }
  expectNoValidationErrors(*session);
}

// The technique rule of the default emitter sampling (WB_EMITTER_SOLID_ANGLE=2, shared/spherical_triangle.h)
// picks solid angle near a triangle and area sampling further away. Here the switch runs across the visible
// floor (a 2x2 emitter 0.6 above it, ratio 0.4: solid angle within ~1.1 of a triangle's centroid), so MIS
// weighs BRDF samples that hit the light with either technique's pdf: MIS, light sampling alone and BRDF
// sampling alone must agree, and so must area sampling everywhere (0) and the first implementation (1). A pdf
// for MIS that is not the technique's that next-event estimation used, or a technique that does not match its
// pdf, shows here.
TEST(Emitters, TechniqueSwitchKeepsMisConsistent) {
  scene::Scene sc = makeShadowScene().scene;
  sc.lights.clear();
  sc.meshes.resize(1);
  sc.instances.resize(1);
  gpu::Material emitter = lambert(glm::vec3(0.0f));
  emitter.emissive = glm::vec3(2.0f);
  sc.materials.push_back(emitter);
  sc.meshes.push_back(quadMesh(1.0f, int(sc.materials.size() - 1)));
  glm::mat4 t(1.0f);
  t[1][1] = -1.0f, t[2][2] = -1.0f;  // facing the floor
  t[3] = glm::vec4(0.3f, 0.6f, 0.0f, 1.0f);
  sc.instances.push_back({1, t, "emitter"});
  sc.camera.eye = glm::vec3(0.0f, 2.0f, 3.0f);
  constexpr float kRatio = 0.4f;
  // The rule switches on the floor in view: below the light solid angle, 1.5 away area sampling.
  const glm::vec3 q0(-0.7f, 0.6f, 1.0f), q1(1.3f, 0.6f, -1.0f),
      q2(1.3f, 0.6f, 1.0f);  // one triangle of the quad
  const glm::vec3 n = glm::cross(q1 - q0, q2 - q0);
  EXPECT_TRUE(gpu::triangleLightUseSolidAngle(glm::vec3(0.6f, 0.0f, 0.3f), q0, q1, q2, n, kRatio));
  EXPECT_FALSE(gpu::triangleLightUseSolidAngle(glm::vec3(-1.0f, 0.0f, -1.0f), q0, q1, q2, n, kRatio));
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings.width = 24;
  o.settings.height = 24;
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.maxBounces = 1;
  o.settings.defines = {{"WB_EMITTER_SOLID_ANGLE_RATIO", "0.4"}};
  auto session = makeSession(o);
  render::RenderSettings mis = o.settings, lightOnly = o.settings, brdfOnly = o.settings;
  lightOnly.mis = false;
  brdfOnly.nee = false;
  const Estimate eMis = estimateMean(*session, mis, 12, 16, 100);
  const Estimate eLight = estimateMean(*session, lightOnly, 12, 16, 200);
  const Estimate eBrdf = estimateMean(*session, brdfOnly, 12, 64, 300);
  // The other techniques are shader variants: sessions of their own.
  render::SessionOptions areaOptions = o, firstOptions = o;
  areaOptions.settings.defines = {{"WB_EMITTER_SOLID_ANGLE", "0"}};
  firstOptions.settings.defines = {{"WB_EMITTER_SOLID_ANGLE", "1"}};
  auto areaSession = makeSession(areaOptions);
  auto firstSession = makeSession(firstOptions);
  const Estimate eArea = estimateMean(*areaSession, areaOptions.settings, 12, 16, 400);
  const Estimate eFirst = estimateMean(*firstSession, firstOptions.settings, 12, 16, 500);
  for (const auto& [name, e] : {std::pair{"mis", &eMis},
                                {"light only", &eLight},
                                {"brdf only", &eBrdf},
                                {"area sampling", &eArea},
                                {"first implementation", &eFirst}}) {
    EXPECT_EQ(e->nonFinite, 0u) << name;
    EXPECT_EQ(e->dropped, 0u) << name;
    EXPECT_LT(e->sigma, 0.01 * e->mean) << name << ": too noisy to compare";
  }
  expectAgree("mis", eMis, "light only", eLight);
  expectAgree("mis", eMis, "brdf only", eBrdf);
  expectAgree("light only", eLight, "brdf only", eBrdf);
  expectAgree("mis", eMis, "area sampling mis", eArea);
  expectAgree("mis", eMis, "first impl. mis", eFirst);
  expectAgree("area sampling mis", eArea, "brdf only", eBrdf);
  // Near the light the solid angle technique has less variance than area sampling.
  EXPECT_LT(eMis.sigma, eArea.sigma);
  expectNoValidationErrors(*session);
  expectNoValidationErrors(*areaSession);
  expectNoValidationErrors(*firstSession);
}

// Rotating the map by a full turn changes nothing (up to float rounding of the rotation); intensity 2 doubles
// every pixel exactly (same samples: importance sampling, MIS and Russian roulette do not depend on
// intensity).
TEST(Environment, FullTurnRotationIsIdentityAndIntensityScales) {
  render::SessionOptions o;
  o.sceneData = makeEnvSpheresScene();
  o.settings = envSettings();
  auto session = makeSession(o);
  auto renderWith = [&](float rotationDeg, float intensity) {
    render::RenderSettings s = o.settings;
    s.envRotationDeg = rotationDeg;
    s.envIntensity = intensity;
    session->pathTracer().setSettings(s);
    session->render(8);
    EXPECT_EQ(session->pathTracer().readCounters().droppedSamples, 0u);
    return session->image();
  };
  const auto base = renderWith(0.0f, 1.0f);
  const auto turned = renderWith(360.0f, 1.0f);
  const auto quarter = renderWith(90.0f, 1.0f);
  const auto doubled = renderWith(0.0f, 2.0f);
  const double m0 = imageMean(base), m360 = imageMean(turned), m90 = imageMean(quarter),
               m2 = imageMean(doubled);
  std::printf("  mean: rot 0 %.6f, rot 360 %.6f, rot 90 %.6f, intensity 2 %.6f (ratio %.6f)\n", m0, m360, m90,
              m2, m2 / m0);
  EXPECT_NEAR(m360 / m0, 1.0, 2e-3);
  EXPECT_NEAR(m2 / m0, 2.0, 1e-4);
  double maxRel360 = 0, maxRel2 = 0, maxRel90 = 0;
  size_t differ360 = 0;
  for (size_t i = 0; i < base.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double b = base.pixels[i], scale = std::max(b, 1e-3);
    const double r360 = std::abs(turned.pixels[i] - b) / scale;
    maxRel360 = std::max(maxRel360, r360);
    differ360 += r360 > 0.05;
    maxRel2 = std::max(maxRel2, std::abs(doubled.pixels[i] - 2.0 * b) / (2.0 * scale));
    maxRel90 = std::max(maxRel90, std::abs(quarter.pixels[i] - b) / scale);
  }
  std::printf(
      "  max per-pixel relative difference: rot 360 %.2e (%zu channels > 5%%), intensity 2 %.2e, rot 90 "
      "%.2e\n",
      maxRel360, differ360, maxRel2, maxRel90);
  EXPECT_LT(maxRel2, 1e-4);
  // A full turn moves directions by ~1e-7 rad: only samples right on a texel edge may change.
  EXPECT_LE(differ360, base.pixels.size() / 4 / 100) << "more than 1% of pixel channels changed by > 5%";
  EXPECT_GT(maxRel90, 0.1) << "a quarter turn should visibly change the image (the rotation is applied)";
  expectNoValidationErrors(*session);
}
