// The path tracer's sun of angular size (shaders/shared/sun.h): a diffuse plane under a cone sun converges to
// the analytic irradiance, with MIS, light sampling alone and BRDF sampling alone (a sun counted twice or not
// at all by one strategy shows as a bias), also when the cone crosses the horizon; a glossy surface
// reflecting the sun agrees across the strategies; a delta sun and the real sun's 0.53 degrees agree; the
// camera sees the disc's radiance; `--sun-angle` (RenderSettings::sunAngleDeg) sizes a scene's delta sun.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "gpu_fixture.h"
#include "pt_helpers.h"
#include "shared/sun.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

constexpr float kIrradiance = 3.0f;
constexpr float kAlbedo = 0.8f;

// A large plane at y = 0 of `floor`, a sun shining toward `toSun` with half-angle `halfAngleDeg` (0: delta),
// a camera at `eye` looking at the origin. Meant for a black environment.
scene::Scene sunScene(glm::vec3 toSun, float halfAngleDeg, gpu::Material floor, glm::vec3 eye) {
  scene::Scene sc;
  sc.sourcePath = "sun-test";
  sc.materials = {floor};
  sc.materialNames = {"floor"};
  sc.meshes = {quadMesh(50.0f, 0)};
  sc.instances.push_back({0, glm::mat4(1.0f), "floor"});
  gpu::DirectionalLight sun{};
  sun.direction = -glm::normalize(toSun);
  sun.cosAngularRadius = std::cos(glm::radians(halfAngleDeg));
  sun.radiance = glm::vec3(kIrradiance);
  sc.lights.push_back(sun);
  sc.camera.eye = eye;
  sc.camera.target = glm::vec3(0.0f);
  sc.camera.up = std::abs(glm::normalize(eye).y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  sc.camera.yfov = 0.5f;
  sc.bounds = {glm::vec3(-50, 0, -50), glm::vec3(50, 0.1f, 50)};
  return sc;
}

glm::vec3 elevated(float elevationDeg) {
  const float e = glm::radians(elevationDeg);
  return glm::vec3(std::cos(e), std::sin(e), 0.0f);
}

// What a Lambertian plane (normal +Y) of albedo kAlbedo reflects under the sun: albedo / pi times the
// integral over the cone, clipped at the horizon, of the disc's radiance times cos theta (midpoint rule,
// double).
double diffusePlaneRadiance(glm::vec3 toSun, float halfAngleDeg) {
  const double cosMax = std::cos(glm::radians(double(halfAngleDeg)));
  const double l = gpu::sunDiscRadiance(glm::vec3(kIrradiance), float(cosMax)).x;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(toSun));
  glm::vec3 tf, bf;
  gpu::buildOrthonormalBasis(glm::vec3(axis), tf, bf);
  const glm::dvec3 t(tf), b(bf);
  const int steps = 1000;
  const double r = std::acos(cosMax);
  double sum = 0;
  for (int i = 0; i < steps; ++i) {
    const double a = (i + 0.5) * r / steps;
    for (int j = 0; j < steps; ++j) {
      const double phi = (j + 0.5) * 2.0 * std::numbers::pi / steps;
      const glm::dvec3 w = std::cos(a) * axis + std::sin(a) * (std::cos(phi) * t + std::sin(phi) * b);
      sum += std::max(0.0, w.y) * std::sin(a);
    }
  }
  return kAlbedo / std::numbers::pi * l * sum * (r / steps) * (2.0 * std::numbers::pi / steps);
}

render::RenderSettings blackEnvironment() {
  render::RenderSettings s;
  s.width = 32;
  s.height = 32;
  s.envColor = glm::vec3(0.0f);
  s.maxBounces = 4;
  return s;
}

void expectClean(const char* what, const Estimate& e) {
  EXPECT_EQ(e.dropped, 0u) << what;
  EXPECT_EQ(e.nonFinite, 0u) << what;
  EXPECT_LT(e.sigma, 0.02 * e.mean) << what << ": too noisy for the comparison to mean anything";
}

void expectNear(const char* what, const Estimate& e, double expected) {
  const double z = std::abs(e.mean - expected) / e.sigma;
  std::printf("  %-26s %.5f +- %.5f  expected %.5f  -> %.2f sigma\n", what, e.mean, e.sigma, expected, z);
  EXPECT_LT(z, 3.5) << what;
}

void expectAgree(const char* a, const Estimate& ea, const char* b, const Estimate& eb) {
  const double z = std::abs(ea.mean - eb.mean) / std::sqrt(ea.sigma * ea.sigma + eb.sigma * eb.sigma);
  std::printf("  %-26s %.5f +- %.5f  vs  %-14s %.5f +- %.5f  -> %.2f sigma\n", a, ea.mean, ea.sigma, b,
              eb.mean, eb.sigma, z);
  EXPECT_LT(z, 3.5) << a << " vs " << b;
}

// MIS, light sampling alone (the miss shader gives the disc weight 0) and BRDF sampling alone (no NEE: the
// disc is found by escaping rays only), each against `expected`.
void expectEveryStrategy(const scene::Scene& sc, double expected, uint32_t seedBase) {
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings = blackEnvironment();
  auto session = makeSession(o);
  render::RenderSettings mis = o.settings, lightOnly = o.settings, brdfOnly = o.settings;
  lightOnly.mis = false;
  brdfOnly.nee = false;
  const Estimate eMis = estimateMean(*session, mis, 12, 16, seedBase);
  const Estimate eLight = estimateMean(*session, lightOnly, 12, 16, seedBase + 100);
  const Estimate eBrdf = estimateMean(*session, brdfOnly, 12, 64, seedBase + 200);
  expectClean("mis", eMis);
  expectClean("light only", eLight);
  expectClean("brdf only", eBrdf);
  expectNear("mis", eMis, expected);
  expectNear("light only", eLight, expected);
  expectNear("brdf only", eBrdf, expected);
  expectNoValidationErrors(*session);
}

}  // namespace

// Sun 60 degrees high, 40 degrees across: the whole cone is above the plane, which receives E sin(60
// degrees), as from a delta sun.
TEST(Sun, ConeSunLightsADiffusePlaneWithItsIrradiance) {
  const glm::vec3 toSun = elevated(60.0f);
  const double expected = diffusePlaneRadiance(toSun, 20.0f);
  EXPECT_NEAR(expected, kAlbedo / std::numbers::pi * kIrradiance * std::sin(glm::radians(60.0)),
              1e-4 * expected);
  expectEveryStrategy(sunScene(toSun, 20.0f, lambert(glm::vec3(kAlbedo)), glm::vec3(0, 3, 0)), expected, 100);
}

// Sun 2 degrees high, 50 degrees across: the horizon cuts the cone; the plane receives the clipped integral, far
// from the delta sun's E sin(2 degrees).
TEST(Sun, ConeSunCrossingTheHorizon) {
  const glm::vec3 toSun = elevated(2.0f);
  const double expected = diffusePlaneRadiance(toSun, 25.0f);
  const double delta = kAlbedo / std::numbers::pi * kIrradiance * std::sin(glm::radians(2.0));
  std::printf("  clipped cone %.5f, delta sun %.5f\n", expected, delta);
  EXPECT_GT(expected, 2.0 * delta);
  expectEveryStrategy(sunScene(toSun, 25.0f, lambert(glm::vec3(kAlbedo)), glm::vec3(0, 3, 0)), expected, 400);
}

// A rough metal seen in the mirror direction of a 10 degree sun: BRDF sampling finds the disc often, so MIS
// weighs both strategies heavily; MIS, light sampling alone and BRDF sampling alone agree (no closed form: a
// sun counted by both strategies, or a weight from the wrong pdf, shows as a disagreement).
TEST(Sun, GlossyReflectionOfTheSunAgreesAcrossStrategies) {
  const glm::vec3 toSun = glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f));
  const glm::vec3 eye = 3.0f * glm::normalize(glm::vec3(-0.5f, 1.0f, 0.0f));
  render::SessionOptions o;
  o.sceneData = sunScene(toSun, 5.0f, pbr(glm::vec3(0.9f), 1.0f, 0.25f), eye);
  o.settings = blackEnvironment();
  auto session = makeSession(o);
  render::RenderSettings mis = o.settings, lightOnly = o.settings, brdfOnly = o.settings;
  lightOnly.mis = false;
  brdfOnly.nee = false;
  const Estimate eMis = estimateMean(*session, mis, 12, 16, 700);
  const Estimate eLight = estimateMean(*session, lightOnly, 12, 16, 800);
  const Estimate eBrdf = estimateMean(*session, brdfOnly, 12, 16, 900);
  expectClean("mis", eMis);
  expectClean("light only", eLight);
  expectClean("brdf only", eBrdf);
  expectAgree("mis", eMis, "light only", eLight);
  expectAgree("mis", eMis, "brdf only", eBrdf);
  expectAgree("light only", eLight, "brdf only", eBrdf);
  expectNoValidationErrors(*session);
}

// The shadow scene (a box over a plane) lit by a delta sun and by the real sun's 0.53 degrees
// (`--sun-angle`): the same image within noise.
TEST(Sun, DeltaSunAndTheRealSunsSizeAgree) {
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings = blackEnvironment();
  auto session = makeSession(o);
  render::RenderSettings delta = o.settings, real = o.settings;
  delta.sunAngleDeg = 0.0f;
  real.sunAngleDeg = 0.53f;
  const Estimate eDelta = estimateMean(*session, delta, 12, 16, 1000);
  const Estimate eReal = estimateMean(*session, real, 12, 16, 1100);
  expectClean("delta", eDelta);
  expectClean("0.53 degrees", eReal);
  expectAgree("delta sun", eDelta, "0.53 degrees", eReal);
  expectNoValidationErrors(*session);
}

// A camera looking at a 10 degree sun sees its disc's radiance E / (pi sin^2 r) inside the cone and the black
// environment around it; `--sun-angle 0` makes the scene's sun a delta light, which no ray sees.
TEST(Sun, CameraSeesTheDiscsRadiance) {
  const glm::vec3 toSun = elevated(50.0f);
  scene::Scene sc = sunScene(toSun, 0.0f, lambert(glm::vec3(kAlbedo)), glm::vec3(0.0f));
  sc.camera.eye = glm::vec3(0.0f, 1.0f, 0.0f);
  sc.camera.target = sc.camera.eye + toSun;
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings = blackEnvironment();
  o.settings.sunAngleDeg = 10.0f;  // the scene's light is a delta light
  auto session = makeSession(o);
  session->render(4);
  const float l = gpu::sunDiscRadiance(glm::vec3(kIrradiance), std::cos(glm::radians(5.0f))).x;
  auto img = session->image();
  const uint32_t c = o.settings.width / 2;
  EXPECT_NEAR(img.at(c, c, 0), l, 1e-5f * l);  // well inside the disc (its radius is ~5 pixels)
  EXPECT_EQ(img.at(0, 0, 0), 0.0f);            // the corners are outside it
  EXPECT_EQ(img.at(o.settings.width - 1, 0, 1), 0.0f);
  render::RenderSettings delta = o.settings;
  delta.sunAngleDeg = 0.0f;
  session->pathTracer().setSettings(delta);
  session->render(4);
  img = session->image();
  EXPECT_EQ(img.at(c, c, 0), 0.0f);
  expectNoValidationErrors(*session);
}
