// Statistical regression test: small renders against stored low-resolution references (tests/data/stat_refs/:
// per scene the mean of many independent runs and the variance of that mean, alpha = degrees of freedom),
// compared by the per-pixel variance-aware test. Noise passes; a change that biases the renderer fails
// (checked here by scaling the same renders by 1.02).
//
// Regenerate the references (only after an intended change of the expected image):
//   WB_WRITE_STAT_REFS=1 build/test_eval_gpu --gtest_filter='StatRegression.*'
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "common/paths.h"
#include "eval/metrics.h"
#include "gpu_runs.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

const std::filesystem::path kRefDir = std::filesystem::path(WB_SOURCE_DIR) / "tests/data/stat_refs";
constexpr uint32_t kRuns = 8, kRefRuns = 48, kRefSppFactor = 4;

struct Case {
  const char* name;
  render::SessionOptions options;
  uint32_t spp;
};

Case cornell() {
  Case c{"cornell", {}, 64};
  c.options.scenePath = (sharedDir() / "reference/cornell.gltf").string();
  c.options.settings.envColor = glm::vec3(0.0f);
  c.options.settings.maxBounces = 64;
  return c;
}

Case shadow() {
  Case c{"shadow", {}, 16};
  c.options.sceneData = makeShadowScene().scene;
  c.options.settings.envColor = glm::vec3(0.0f);
  return c;
}

Case metalFurnace() {
  Case c{"metal_furnace", {}, 16};
  gpu::Material m = lambert(glm::vec3(1.0f, 0.78f, 0.34f));
  m.metallic = 1.0f;
  m.roughness = 0.4f;
  m.specularFactor = 1.0f;
  c.options.sceneData = makeFurnaceScene(m);
  c.options.settings.envColor = glm::vec3(1.0f, 0.9f, 0.8f);
  return c;
}

void runCase(Case c) {
  c.options.settings.width = c.options.settings.height = 32;
  auto session = makeSession(c.options);
  const auto meanPath = kRefDir / (std::string(c.name) + ".mean.exr");
  const auto varPath = kRefDir / (std::string(c.name) + ".var.exr");
  const char* write = std::getenv("WB_WRITE_STAT_REFS");
  if (write && *write && std::string(write) != "0") {
    const auto ref = eval::estimateFromRuns(
        renderRuns(*session, c.options.settings, kRefRuns, c.spp * kRefSppFactor, 5000));
    std::filesystem::create_directories(kRefDir);
    auto var = ref.varianceOfMean;
    for (size_t i = 3; i < var.pixels.size(); i += 4) var.pixels[i] = float(ref.dof);
    eval::writeExr(meanPath, ref.mean);
    eval::writeExr(varPath, var);
    std::printf("wrote %s and %s\n", meanPath.c_str(), varPath.c_str());
  }
  ASSERT_TRUE(std::filesystem::exists(meanPath)) << meanPath << " missing (see the comment at the top)";
  eval::MeanEstimate ref;
  ref.mean = eval::readExr(meanPath);
  ref.varianceOfMean = eval::readExr(varPath);
  ref.dof = ref.varianceOfMean.pixels.at(3);

  const auto runs = renderRuns(*session, c.options.settings, kRuns, c.spp, 1);
  // The test's own 8 runs give a noisy variance (heavy-tailed pixels: a set of runs without a rare bright
  // path has both a low mean and a low variance); predict it from the reference's 48 runs instead.
  eval::StatTestOptions opt;
  opt.testVarianceFromReference = double(kRefRuns * kRefSppFactor) / double(kRuns);
  const auto result = eval::statisticalTest(eval::estimateFromRuns(runs), ref, opt);
  std::printf("%s: %s\n", c.name, result.summary().c_str());
  EXPECT_TRUE(result.pass) << c.name << ": " << result.summary();

  auto scaled = runs;
  for (auto& img : scaled)
    for (float& v : img.pixels) v *= 1.02f;
  const auto biased = eval::statisticalTest(eval::estimateFromRuns(scaled), ref, opt);
  std::printf("%s x 1.02: %s\n", c.name, biased.summary().c_str());
  EXPECT_FALSE(biased.pass) << c.name << " x 1.02 should fail: " << biased.summary();
  expectNoValidationErrors(*session);
}

}  // namespace

TEST(StatRegression, Cornell) {
  runCase(cornell());
}
TEST(StatRegression, ShadowSun) {
  runCase(shadow());
}
TEST(StatRegression, MetalFurnace) {
  runCase(metalFurnace());
}
