// Scene-driven specialisation: the specialised build renders the same image as the all-features build,
// carries only the stages the scene needs, and variants are cached like any other shader.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "scene/features.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

eval::ImageRGBA render(render::SessionOptions o, bool generic) {
  o.settings.width = 32;
  o.settings.height = 32;
  o.settings.generic = generic;
  auto session = makeSession(o);
  EXPECT_EQ(session->pathTracer().features().generic, generic);
  session->render(4);
  expectNoValidationErrors(*session);
  return session->image();
}

eval::ImageRGBA renderScene(const std::string& path, bool generic) {
  render::SessionOptions o;
  o.scenePath = path;
  return render(o, generic);
}

// A scene built in code, lit by its lights alone.
eval::ImageRGBA renderSceneData(const scene::Scene& scene, bool generic) {
  render::SessionOptions o;
  o.sceneData = scene;
  o.settings.envColor = glm::vec3(0.0f);
  return render(o, generic);
}

eval::ImageRGBA renderDefault(bool generic) {
  return renderScene("", generic);
}

// Same sample streams, same maths: equal up to floating-point reassociation in the compiled code.
void expectSameImage(const eval::ImageRGBA& a, const eval::ImageRGBA& b) {
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double meanA = 0, meanB = 0, maxRel = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    meanA += a.pixels[i];
    meanB += b.pixels[i];
    maxRel = std::max(maxRel,
                      std::abs(double(a.pixels[i]) - b.pixels[i]) / (std::abs(double(b.pixels[i])) + 1e-2));
  }
  EXPECT_NEAR(meanA / meanB, 1.0, 1e-4);
  EXPECT_LT(maxRel, 1e-2) << "per-pixel difference beyond floating-point noise";
}

// A function, not a global: paths resolve when a test runs (tests may point WB_ROOT elsewhere first).
std::string helmetPath() {
  return (sharedDir() / "assets/gltf/DamagedHelmet/DamagedHelmet.gltf").string();
}

}  // namespace

TEST(Specialization, DefaultSceneFeatures) {
  const auto scene = scene::loadGltf(defaultScenePath());
  const auto f = scene::analyzeFeatures(scene, scene::EnvironmentKind::Constant);
  EXPECT_FALSE(f.generic);
  EXPECT_TRUE(f.alphaMask);  // the leaf
  EXPECT_FALSE(f.alphaBlend);
  EXPECT_TRUE(f.emissive);  // the ceiling panel
  EXPECT_TRUE(f.textures);
  EXPECT_EQ(f.directionalLights, 1u);
  EXPECT_TRUE(f.specular);    // Lambert walls: specularFactor 0
  EXPECT_TRUE(f.reflectors);  // the glossy spheres: reflector guiding
  EXPECT_NE(std::find(f.extensions.begin(), f.extensions.end(), "KHR_lights_punctual"), f.extensions.end());
  EXPECT_NE(scene::describeFeatures(f).find("KHR_materials_specular"), std::string::npos);
  EXPECT_EQ(render::PathTracer::stageKeys(f, false).size(), 5u)
      << "alpha-masked leaf needs the any-hit stage";
}

TEST(Specialization, OpaqueSceneHasNoAnyHitStageAndNoTextures) {
  const auto f = scene::analyzeFeatures(makeShadowScene().scene, scene::EnvironmentKind::None);
  EXPECT_FALSE(f.anyAlpha());
  EXPECT_FALSE(f.textures);
  EXPECT_FALSE(f.emissive);
  EXPECT_FALSE(f.normalMaps);
  EXPECT_FALSE(f.reflectors) << "no glossy reflector: the build leaves reflector guiding out";
  const auto keys = render::PathTracer::stageKeys(f, false);
  ASSERT_EQ(keys.size(), 4u);
  for (const auto& k : keys) EXPECT_NE(k.path.extension(), ".rahit");
  const auto defines = scene::featureDefines(f);
  EXPECT_NE(std::find(defines.begin(), defines.end(), shader::Define{"WB_LIGHT_COUNT", "1u"}), defines.end());
  EXPECT_NE(std::find(defines.begin(), defines.end(), shader::Define{"WB_ENV_MODE", "0"}), defines.end());
  EXPECT_NE(std::find(defines.begin(), defines.end(), shader::Define{"WB_HAS_REFLECTORS", "0"}),
            defines.end());
  // A live edit that makes a material a smooth metal needs a build with the guiding code.
  auto materials = makeShadowScene().scene.materials;
  EXPECT_TRUE(scene::featuresCover(f, materials));
  materials.at(0).metallic = 1.0f;
  materials.at(0).roughness = 0.2f;
  EXPECT_FALSE(scene::featuresCover(f, materials));
}

TEST(Specialization, SpecialisedAndGenericRenderTheSameImage) {
  expectSameImage(renderDefault(false), renderDefault(true));
}

// An opaque scene without KHR_materials_specular and without directional lights: the specialised build has no
// any-hit stage, no specular-extension code and no light loop, and still renders the generic build's image.
TEST(Specialization, OpaqueTexturedModelRendersTheSameImageSpecialised) {
  const auto scene = scene::loadGltf(helmetPath());
  const auto f = scene::analyzeFeatures(scene, scene::EnvironmentKind::Constant);
  EXPECT_FALSE(f.anyAlpha());
  EXPECT_FALSE(f.specular);
  EXPECT_TRUE(f.normalMaps);
  EXPECT_TRUE(f.textures);
  EXPECT_EQ(f.directionalLights, 0u);
  EXPECT_EQ(render::PathTracer::stageKeys(f, false).size(), 4u);
  const auto defines = scene::featureDefines(f);
  EXPECT_NE(std::find(defines.begin(), defines.end(), shader::Define{"WB_HAS_SPECULAR", "0"}), defines.end());
  expectSameImage(renderScene(helmetPath(), false), renderScene(helmetPath(), true));
}

// The generic build sizes its payload's shadow requests for kGenericMaxLights directional lights; a scene
// with more gets room for all of them (a define), so every light still shades, as in the specialised build.
TEST(Specialization, GenericBuildShadesMoreDirectionalLightsThanItsDefaultCapacity) {
  auto scene = makeShadowScene().scene;
  for (uint32_t i = 0; i < scene::kGenericMaxLights + 1; ++i) {
    auto light = scene.lights[0];
    const float a = 0.7f * float(i);
    light.direction = glm::normalize(glm::vec3(std::cos(a), -1.5f, std::sin(a)));
    light.radiance = glm::vec3(0.4f);
    scene.lights.push_back(light);
  }
  const auto defines = scene::featureDefines(scene::genericFeatures(uint32_t(scene.lights.size())));
  EXPECT_NE(std::find(defines.begin(), defines.end(),
                      shader::Define{"WB_GENERIC_MAX_LIGHTS", std::to_string(scene.lights.size()) + "u"}),
            defines.end());
  expectSameImage(renderSceneData(scene, false), renderSceneData(scene, true));
}

TEST(Specialization, SwitchingVariantsReusesCompiledShaders) {
  render::SessionOptions o;
  o.sceneData = makeShadowScene().scene;
  o.settings.width = 16;
  o.settings.height = 16;
  o.settings.envColor = glm::vec3(0.0f);
  auto session = makeSession(o);
  auto& tracer = session->pathTracer();
  const auto specialised = tracer.features();
  EXPECT_FALSE(specialised.generic);
  EXPECT_TRUE(tracer.setFeatures(scene::genericFeatures()));
  const auto before = session->library().stats().compiles;
  EXPECT_TRUE(tracer.setFeatures(specialised));  // back: every stage comes from the cache
  EXPECT_EQ(session->library().stats().compiles, before);
  EXPECT_FALSE(tracer.setFeatures(specialised));
  session->render(1);
  expectNoValidationErrors(*session);
}

// CPU devices (lavapipe) get code shaped for their JIT (WB_CPU_DEVICE=1: the sampler in one loop instead of
// seven inlined copies), GPUs straight-line code; a variant of its own in the cache, unless the user's
// --define chose.
TEST(Specialization, CpuDeviceCodeIsAVariantOfItsOwn) {
  auto f = scene::analyzeFeatures(scene::loadGltf(defaultScenePath()), scene::EnvironmentKind::Constant);
  const shader::Define cpu{"WB_CPU_DEVICE", "1"};
  for (const auto& k : render::PathTracer::stageKeys(f, true))
    EXPECT_NE(std::find(k.defines.begin(), k.defines.end(), cpu), k.defines.end()) << k.path;
  for (const auto& k : render::PathTracer::stageKeys(f, false))
    EXPECT_EQ(std::find(k.defines.begin(), k.defines.end(), cpu), k.defines.end()) << k.path;
  f.extraDefines = {{"WB_CPU_DEVICE", "0"}};
  for (const auto& k : render::PathTracer::stageKeys(f, true)) {
    EXPECT_EQ(std::find(k.defines.begin(), k.defines.end(), cpu), k.defines.end()) << k.path;
    EXPECT_NE(std::find(k.defines.begin(), k.defines.end(), shader::Define{"WB_CPU_DEVICE", "0"}),
              k.defines.end());
  }
}

// Both shapes draw the same samples for the same dimensions: the same image (WB_CPU_DEVICE_CODE forces one).
TEST(Specialization, CpuAndGpuShapedCodeRenderTheSameImage) {
  auto renderShaped = [](bool cpu) {
    ::setenv("WB_CPU_DEVICE_CODE", cpu ? "1" : "0", 1);
    render::SessionOptions o;
    o.settings.width = 32;
    o.settings.height = 32;
    auto session = makeSession(o);
    EXPECT_EQ(session->pathTracer().cpuDeviceCode(), cpu);
    session->render(4);
    expectNoValidationErrors(*session);
    ::unsetenv("WB_CPU_DEVICE_CODE");
    return session->image();
  };
  expectSameImage(renderShaped(true), renderShaped(false));
}
