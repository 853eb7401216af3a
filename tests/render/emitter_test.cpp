// Area lights: next-event estimation of emissive triangles with MIS is unbiased (it agrees with BRDF sampling
// alone and with light sampling alone), and a single-sided emitter lights nothing behind it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "scene/emitters.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;

namespace {

struct MeanEstimate {
  double mean = 0, standardError = 0;
  double pixelNoise = 0;  // mean squared per-pixel difference between the first two seeds' images
};

// Mean image value over independent seeds, with the standard error of that mean.
MeanEstimate cornellMean(render::RenderSettings s, int seeds, uint32_t spp) {
  render::SessionOptions o;
  o.scenePath = (sharedDir() / "reference/cornell.gltf").string();
  s.width = 24;
  s.height = 24;
  s.envColor = glm::vec3(0.0f);
  s.maxBounces = 6;
  std::vector<double> means;
  std::vector<eval::ImageRGBA> firstTwo;
  for (int k = 0; k < seeds; ++k) {
    s.seed = 1000u + k;
    o.settings = s;
    auto session = makeSession(o);
    session->render(spp);
    const auto img = session->image();
    if (firstTwo.size() < 2) firstTwo.push_back(img);
    const auto st = imageStats(img);
    EXPECT_EQ(st.nonFinite, 0u);
    means.push_back((st.mean[0] + st.mean[1] + st.mean[2]) / 3.0);
    expectNoValidationErrors(*session);
  }
  MeanEstimate e;
  for (double m : means) e.mean += m / seeds;
  double var = 0;
  for (double m : means) var += (m - e.mean) * (m - e.mean) / (seeds - 1);
  e.standardError = std::sqrt(var / seeds);
  for (size_t i = 0; i < firstTwo[0].pixels.size(); ++i) {
    const double d = firstTwo[0].pixels[i] - firstTwo[1].pixels[i];
    e.pixelNoise += d * d / double(firstTwo[0].pixels.size());
  }
  return e;
}

}  // namespace

TEST(Emitters, DefaultSceneCeilingPanelIsFound) {
  const auto scene = scene::loadGltf(defaultScenePath());
  const auto tris = scene::emissiveTriangles(scene);
  ASSERT_EQ(tris.size(), 2u) << "the ceiling panel is one quad";
  double area = 0;
  for (const auto& t : tris) area += t.area;
  EXPECT_GT(area, 0.01);
  const auto w = scene::emitterWeights(scene, tris);
  EXPECT_GT(w[0], 0.0);
}

TEST(Emitters, NeeWithMisAgreesWithBrdfOnlyAndLightOnly) {
  render::RenderSettings mis, brdf, light;
  brdf.nee = false;
  light.mis = false;
  const auto a = cornellMean(mis, 6, 16);
  const auto b = cornellMean(brdf, 6, 16);
  const auto c = cornellMean(light, 6, 16);
  // Each pair within 4 standard errors of the difference: a biased strategy fails this, noise does not.
  auto agree = [](MeanEstimate x, MeanEstimate y) {
    return std::abs(x.mean - y.mean) <=
           4.0 * std::sqrt(x.standardError * x.standardError + y.standardError * y.standardError);
  };
  EXPECT_TRUE(agree(a, b)) << a.mean << " +- " << a.standardError << " vs BRDF only " << b.mean << " +- "
                           << b.standardError;
  EXPECT_TRUE(agree(a, c)) << a.mean << " +- " << a.standardError << " vs light only " << c.mean << " +- "
                           << c.standardError;
  // And NEE is the point: far less per-pixel noise than BRDF sampling alone on this small light.
  EXPECT_LT(a.pixelNoise * 4.0, b.pixelNoise) << a.pixelNoise << " vs " << b.pixelNoise;
}

TEST(Emitters, SingleSidedEmitterLightsOnlyInFront) {
  // A floor and an emissive quad 1 m above it, facing the floor or facing away (up). Facing away, the floor
  // far from it (the image corners) stays exactly black; facing the floor, it is lit.
  auto cornerSum = [](bool facingFloor) {
    scene::Scene sc = makeShadowScene().scene;
    sc.lights.clear();
    sc.meshes.resize(1);
    sc.instances.resize(1);
    gpu::Material emitter = lambert(glm::vec3(0.0f));
    emitter.emissive = glm::vec3(5.0f);
    sc.materials.push_back(emitter);
    sc.meshes.push_back(quadMesh(0.5f, int(sc.materials.size() - 1)));  // normal +Y
    glm::mat4 t(1.0f);
    if (facingFloor) t[1][1] = -1.0f, t[2][2] = -1.0f;  // rotate 180 degrees about X: normal -Y
    t[3] = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    sc.instances.push_back({1, t, "emitter"});
    render::SessionOptions o;
    o.sceneData = sc;
    o.settings.width = 32;
    o.settings.height = 32;
    o.settings.envColor = glm::vec3(0.0f);
    auto session = makeSession(o);
    session->render(8);
    const auto img = session->image();
    EXPECT_EQ(imageStats(img).nonFinite, 0u);
    double sum = 0;
    for (uint32_t y : {0u, 31u}) {
      for (uint32_t x : {0u, 31u}) sum += img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2);
    }
    expectNoValidationErrors(*session);
    return sum;
  };
  EXPECT_EQ(cornerSum(false), 0.0) << "the back of a single-sided emitter must not light the floor";
  EXPECT_GT(cornerSum(true), 1e-3) << "facing the floor it lights it";
}

namespace {

eval::ImageRGBA renderCornell(const scene::Scene& scene, const std::vector<gpu::Material>* edit) {
  render::SessionOptions o;
  o.sceneData = scene;
  o.settings.width = 24;
  o.settings.height = 24;
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.maxBounces = 6;
  o.settings.seed = 7;
  auto session = makeSession(o);
  if (edit) session->gpuScene().updateMaterials(*edit);
  session->render(16);
  expectNoValidationErrors(*session);
  return session->image();
}

double meanOf(const eval::ImageRGBA& img) {
  const auto s = imageStats(img);
  EXPECT_EQ(s.nonFinite, 0u);
  return (s.mean[0] + s.mean[1] + s.mean[2]) / 3.0;
}

}  // namespace

// Live material edits rebuild the area lights' table, so next-event estimation samples what is there now:
// twice the emission renders exactly twice the image (same samples), and a wall made emissive by an edit
// renders what a scene loaded with that emission renders.
TEST(Emitters, MaterialEditsRebuildTheLightTable) {
  const auto scene = scene::loadGltf(sharedDir() / "reference/cornell.gltf");
  const auto& names = scene.materialNames;
  const size_t light = std::find(names.begin(), names.end(), "cb_light") - names.begin();
  const size_t red = std::find(names.begin(), names.end(), "cb_red") - names.begin();
  ASSERT_LT(light, names.size());
  ASSERT_LT(red, names.size());

  const double base = meanOf(renderCornell(scene, nullptr));
  auto brighter = scene.materials;
  brighter[light].emissive *= 2.0f;
  const double doubled = meanOf(renderCornell(scene, &brighter));
  EXPECT_NEAR(doubled / base, 2.0, 2e-3);

  auto glowing = scene.materials;
  glowing[red].emissive = glm::vec3(0.5f, 0.05f, 0.05f);
  scene::Scene loaded = scene;
  loaded.materials = glowing;
  const double edited = meanOf(renderCornell(scene, &glowing));
  const double fresh = meanOf(renderCornell(loaded, nullptr));
  EXPECT_NEAR(edited / fresh, 1.0, 1e-3);
  EXPECT_GT(edited, base * 1.05) << "the glowing wall adds light";
}
