// The hybrid modes on the real device (lavapipe here) under the validation layer: ray traced shadow masks
// against the path tracer, reflections that show the reflected object, and hot reload through one
// ShaderLibrary that tracks raster and ray tracing pipelines together.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <thread>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include "common/paths.h"
#include "gpu_fixture.h"
#include "live/hot_reload.h"
#include "eval/metrics.h"
#include "render/hybrid/hybrid_renderer.h"
#include "shared/sun.h"
#include "test_scenes.h"

using namespace wb;
using namespace wb::testing;
using Pass = render::HybridPass;

namespace {

render::SessionOptions hybridOptions(const scene::Scene& sc, render::RenderMode mode, uint32_t size) {
  render::SessionOptions o;
  o.sceneData = sc;
  o.settings.width = size;
  o.settings.height = size;
  o.mode = mode;
  o.hybrid.aoRays = 0;
  o.settings.sunAngleDeg = 0.0f;  // a delta sun: hard shadows
  return o;
}

}  // namespace

TEST(Hybrid, ShadowMaskMatchesThePathTracersLitAndShadowedPixels) {
  ShadowScene s = makeShadowScene();
  auto o = hybridOptions(s.scene, render::RenderMode::Hybrid, 64);
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.aov = true;
  auto session = makeSession(o);
  session->render(1);
  const auto mask = session->hybrid()->readShadowMask();
  const auto hybridImage = session->image();

  // Path tracer: lit/shadowed classification of the plane (the box's albedo AOV is 0: excluded).
  auto& pt = session->pathTracer();
  pt.render(4);
  const auto radiance = pt.readAccumulation();
  const auto albedo = pt.readAov(render::Aov::Albedo);
  const float expectedLit = s.albedo * s.sunRadiance * -s.sunDirection.y / 3.14159265f;
  const int w = 64, h = 64;
  std::vector<int> cls(w * h, 2);  // 0 lit plane, 1 shadowed plane, 2 other or mixed
  for (int i = 0; i < w * h; ++i) {
    const float a = albedo[4 * i];
    if (a < s.albedo - 0.01f) continue;  // box or a pixel the box covers partly
    const float v = radiance[4 * i];
    cls[i] = v > 0.9f * expectedLit ? 0 : v < 0.1f * expectedLit ? 1 : 2;
  }
  int lit = 0, shadowed = 0, edgeMismatch = 0, interiorMismatch = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int c = cls[y * w + x];
      if (c == 2) continue;
      bool interior = true;  // every neighbour in the same class: not an edge pixel
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = std::clamp(x + dx, 0, w - 1), yy = std::clamp(y + dy, 0, h - 1);
          interior = interior && cls[yy * w + xx] == c;
        }
      }
      const bool maskLit = mask[y * w + x] > 127;
      if (maskLit != (c == 0)) {
        (interior ? interiorMismatch : edgeMismatch)++;
        if (interior)
          ADD_FAILURE() << "pixel " << x << "," << y << ": path tracer " << (c ? "shadowed" : "lit")
                        << ", mask " << int(mask[y * w + x]);
      }
      if (interior) (c == 0 ? lit : shadowed)++;
      // The composite agrees with the analytic Lambert value in the sun and is black in the shadow.
      if (interior && c == 0) {
        EXPECT_NEAR(hybridImage.at(x, y, 0), expectedLit, 0.02f * expectedLit);
      }
      if (interior && c == 1) {
        EXPECT_LT(hybridImage.at(x, y, 0), 1e-4f);
      }
    }
  }
  std::printf(
      "shadow mask vs path tracer: %d lit, %d shadowed interior pixels; %d edge, %d interior mismatches\n",
      lit, shadowed, edgeMismatch, interiorMismatch);
  EXPECT_TRUE(session->context().validationEnabled());
  EXPECT_GT(lit, 500);
  EXPECT_GT(shadowed, 50);
  EXPECT_EQ(interiorMismatch, 0);
  EXPECT_LT(edgeMismatch, 40);
  expectNoValidationErrors(*session);
}

TEST(Hybrid, SoftSunShadowsAreGreyOnlyNearTheEdges) {
  ShadowScene s = makeShadowScene();
  auto o = hybridOptions(s.scene, render::RenderMode::Hybrid, 64);
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.sunAngleDeg = 10.0f;
  auto session = makeSession(o);
  session->render(16);  // temporal accumulation: averaged visibility
  const auto mask = session->hybrid()->readShadowMask();
  int grey = 0, black = 0;
  for (uint8_t v : mask) {
    if (v > 20 && v < 235) grey++;
    if (v <= 20) black++;
  }
  std::printf("soft sun: %d penumbra, %d umbra pixels\n", grey, black);
  EXPECT_GT(grey, 20) << "a 10 degree sun should give penumbrae";
  EXPECT_GT(black, 20) << "and still an umbra";
  expectNoValidationErrors(*session);
}

namespace {

// A white plane (albedo 0.8), a black 3x3 box 16 above it, a sun straight above of irradiance 3, a camera
// looking down at the plane from the side (the box is out of view): with a sun of a few degrees, a penumbra
// ~15 pixels wide at 64x64.
scene::Scene highBoxScene() {
  ShadowScene s = makeShadowScene();
  scene::Scene& sc = s.scene;
  sc.meshes[1] = boxMesh(glm::vec3(1.5f, 0.2f, 1.5f), 1);
  sc.instances[1].transform[3] = glm::vec4(0.0f, 16.2f, 0.0f, 1.0f);
  sc.lights[0].direction = glm::vec3(0.0f, -1.0f, 0.0f);
  sc.camera.eye = glm::vec3(0.0f, 3.0f, 4.0f);
  sc.camera.target = glm::vec3(0.0f);
  sc.bounds.max.y = 16.4f;
  return sc;
}

}  // namespace

// The hybrid's shadow rays sample the path tracer's cone (shared/sun.h): with a sun of 4 degrees straight
// above, its image (shadows averaged over 64 frames) and the path tracer's (64 samples) agree pixel by pixel
// within their noise, penumbra included (the statistical image test, eval/metrics.h, on 8 runs of each). The
// test has power: the hybrid with a 2 degree cone fails it, and so did the shadows' running average kept in
// 16-bit floats (0.8% low in the penumbra on lavapipe). Straight above, the cosine varies by 0.06% over the
// cone, so the hybrid's shading with the sun's centre costs nothing here.
TEST(Hybrid, PenumbraAgreesWithThePathTracer) {
  auto o = hybridOptions(highBoxScene(), render::RenderMode::Hybrid, 64);
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.sunAngleDeg = 4.0f;
  o.settings.sampler = render::SamplerKind::Pcg;  // independent runs
  auto session = makeSession(o);
  constexpr uint32_t kRuns = 8, kSamples = 64;
  auto runs = [&](render::RenderMode mode, float sunAngleDeg, uint32_t firstSeed) {
    std::vector<eval::ImageRGBA> out;
    render::RenderSettings s = o.settings;
    s.sunAngleDeg = sunAngleDeg;
    for (uint32_t r = 0; r < kRuns; ++r) {
      s.seed = firstSeed + r;
      session->setMode(mode, s).setSettings(s);
      session->render(kSamples);
      out.push_back(session->image());
    }
    return out;
  };
  const auto pathTraced = eval::estimateFromRuns(runs(render::RenderMode::PathTrace, 4.0f, 1));
  const auto hybrid = runs(render::RenderMode::Hybrid, 4.0f, 101);
  // The penumbra is there: pixels between lit and shadowed in the hybrid's mean.
  const auto mean = eval::estimateFromRuns(hybrid);
  const float lit = 0.8f * 3.0f / 3.14159265f;
  int penumbra = 0;
  for (uint32_t i = 0; i < 64u * 64u; ++i) {
    const float v = float(mean.mean.pixels[4 * i]);
    penumbra += v > 0.1f * lit && v < 0.9f * lit;
  }
  std::printf("penumbra pixels: %d\n", penumbra);
  EXPECT_GT(penumbra, 300);
  const auto same = eval::statisticalTest(eval::estimateFromRuns(hybrid), pathTraced);
  std::printf("hybrid vs path tracer, both 4 degrees: %s\n", same.summary().c_str());
  EXPECT_TRUE(same.pass) << same.summary();
  const auto narrower =
      eval::statisticalTest(eval::estimateFromRuns(runs(render::RenderMode::Hybrid, 2.0f, 201)), pathTraced);
  std::printf("hybrid 2 degrees vs path tracer 4 degrees: %s\n", narrower.summary().c_str());
  EXPECT_FALSE(narrower.pass) << narrower.summary();
  expectNoValidationErrors(*session);
}

// The hybrid's background shows a sun of angular size as the path tracer's camera rays do: its disc's
// radiance E / (pi sin^2 r) inside the cone, the environment around it.
TEST(Hybrid, BackgroundShowsTheSunsDiscLikeThePathTracer) {
  scene::Scene sc = makeShadowScene().scene;
  const glm::vec3 toSun = -sc.lights[0].direction;
  sc.camera.eye = glm::vec3(0.0f, 2.0f, 0.0f);
  sc.camera.target = sc.camera.eye + toSun;
  sc.camera.yfov = 0.5f;
  auto o = hybridOptions(sc, render::RenderMode::Hybrid, 32);
  o.settings.envColor = glm::vec3(0.0f);
  o.settings.sunAngleDeg = 10.0f;
  auto session = makeSession(o);
  session->render(1);
  const float l = gpu::sunDiscRadiance(sc.lights[0].radiance, std::cos(glm::radians(5.0f))).x;
  const auto hybrid = session->image();
  EXPECT_NEAR(hybrid.at(16, 16, 0), l, 1e-5f * l);
  EXPECT_EQ(hybrid.at(0, 0, 0), 0.0f);
  session->setMode(render::RenderMode::PathTrace, o.settings).setSettings(o.settings);
  session->render(1);
  EXPECT_NEAR(session->image().at(16, 16, 0), hybrid.at(16, 16, 0), 1e-5f * l);
  expectNoValidationErrors(*session);
}

TEST(Hybrid, MirrorPlaneReflectsTheColouredBox) {
  scene::Scene sc;
  sc.sourcePath = "mirror-test";
  gpu::Material mirror = lambert(glm::vec3(0.95f));
  mirror.metallic = 1.0f;
  mirror.roughness = 0.0f;
  mirror.specularFactor = 1.0f;
  gpu::Material red = lambert(glm::vec3(0.0f));
  red.emissive = glm::vec3(2.0f, 0.1f, 0.1f);
  sc.materials = {mirror, red};
  sc.materialNames = {"mirror", "red-emitter"};
  const glm::vec3 boxMin(-0.5f, 0.3f, -1.5f), boxMax(0.5f, 1.3f, -0.5f);
  sc.meshes = {quadMesh(3.0f, 0), boxMesh((boxMax - boxMin) * 0.5f, 1)};
  sc.instances.push_back({0, glm::mat4(1.0f), "mirror"});
  glm::mat4 t(1.0f);
  t[3] = glm::vec4((boxMin + boxMax) * 0.5f, 1.0f);
  sc.instances.push_back({1, t, "box"});
  sc.camera.eye = glm::vec3(0.0f, 1.2f, 2.5f);
  sc.camera.target = glm::vec3(0.0f, 0.0f, -0.5f);
  sc.camera.yfov = 0.9f;
  sc.bounds = {glm::vec3(-3, 0, -3), glm::vec3(3, 1.3f, 3)};

  auto o = hybridOptions(sc, render::RenderMode::Reflections, 64);
  o.settings.envColor = glm::vec3(0.3f);
  auto session = makeSession(o);
  session->render(1);
  const auto img = session->image();
  const auto refl = session->hybrid()->readReflection();
  const auto& cam = session->sceneCamera();
  // 0: mirror reflecting the box, 1: mirror reflecting the sky, 2: other / mixed.
  auto classify = [&](float px, float py) {
    glm::vec3 o3, d;
    cameraRay(cam, 64, 64, px, py, o3, d);
    if (hitBox(o3, d, boxMin, boxMax) >= 0.0f || d.y >= 0.0f) return 2;
    const glm::vec3 p = o3 + d * (-o3.y / d.y);
    if (std::abs(p.x) > 2.9f || std::abs(p.z) > 2.9f) return 2;
    return hitBox(p + glm::vec3(0, 1e-4f, 0), glm::vec3(d.x, -d.y, d.z), boxMin, boxMax) >= 0.0f ? 0 : 1;
  };
  int boxPixels = 0, skyPixels = 0;
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      const int c = classify(x + 0.5f, y + 0.5f);
      bool uniform = c != 2;
      for (float dy : {0.0f, 1.0f}) {
        for (float dx : {0.0f, 1.0f}) uniform = uniform && classify(x + dx, y + dy) == c;
      }
      if (!uniform) continue;
      const float r = img.at(x, y, 0), g = img.at(x, y, 1), b = img.at(x, y, 2);
      EXPECT_GT(refl[(y * 64 + x) * 4 + 3], 0.5f) << "mirror pixel " << x << "," << y << " was not traced";
      if (c == 0) {
        boxPixels++;
        EXPECT_GT(r, 1.5f) << x << "," << y;  // ~0.95 * 2 (metal Fresnel at most 1)
        EXPECT_GT(r, 5.0f * g) << x << "," << y;
      } else {
        skyPixels++;
        EXPECT_NEAR(r, g, 0.02f) << x << "," << y;
        EXPECT_NEAR(g, 0.3f * 0.95f, 0.05f) << x << "," << y;
      }
      (void)b;
    }
  }
  std::printf("mirror: %d pixels reflect the box, %d the sky\n", boxPixels, skyPixels);
  EXPECT_GT(boxPixels, 30);
  EXPECT_GT(skyPixels, 100);
  expectNoValidationErrors(*session);
}

// Reflections are traced for smooth metals only by default (--reflection-metallic 0.5); with 0 the smooth
// dielectric gets them too. The depth is a specialisation constant: 0 rebuilds the pipeline and traces none.
TEST(Hybrid, ReflectionsFollowMetalnessAndTheDepthConstant) {
  scene::Scene sc;
  sc.sourcePath = "gloss-test";
  gpu::Material gloss = lambert(glm::vec3(0.5f));
  gloss.metallic = 0.0f;
  gloss.roughness = 0.0f;
  gloss.specularFactor = 1.0f;
  sc.materials = {gloss};
  sc.materialNames = {"smooth-dielectric"};
  sc.meshes = {quadMesh(3.0f, 0)};
  sc.instances.push_back({0, glm::mat4(1.0f), "plane"});
  sc.camera.eye = glm::vec3(0.0f, 1.0f, 2.0f);
  sc.camera.target = glm::vec3(0.0f, 0.0f, -0.5f);
  sc.camera.yfov = 0.9f;
  sc.bounds = {glm::vec3(-3, 0, -3), glm::vec3(3, 0.1f, 3)};
  auto traced = [](const std::vector<float>& refl) {
    size_t n = 0;
    for (size_t i = 3; i < refl.size(); i += 4) n += refl[i] > 0.5f;
    return n;
  };
  auto o = hybridOptions(sc, render::RenderMode::Reflections, 32);
  o.settings.envColor = glm::vec3(0.3f);
  auto session = makeSession(o);
  auto* hybrid = session->hybrid();
  session->render(1);
  EXPECT_EQ(traced(hybrid->readReflection()), 0u) << "a dielectric is not traced by default";
  auto h = hybrid->hybridSettings();
  h.reflectionMinMetallic = 0.0f;
  hybrid->setHybridSettings(h);
  session->render(1);
  const size_t all = traced(hybrid->readReflection());
  EXPECT_GT(all, 32u * 32u / 3) << "the plane covers the lower part of the image";
  const uint32_t builds = hybrid->pipelineBuilds(Pass::Reflection);
  h.reflectionDepth = 0;
  hybrid->setHybridSettings(h);
  EXPECT_EQ(hybrid->pipelineBuilds(Pass::Reflection), builds + 1) << "a new specialisation constant";
  session->render(1);
  EXPECT_EQ(traced(hybrid->readReflection()), 0u);
  expectNoValidationErrors(*session);
}

// Ambient occlusion, the second ray type: the floor right next to a box is occluded, the open floor is not.
TEST(Hybrid, AmbientOcclusionDarkensTheFloorNextToABox) {
  scene::Scene sc;
  sc.sourcePath = "ao-test";
  sc.materials = {lambert(glm::vec3(0.8f))};
  sc.materialNames = {"white"};
  const glm::vec3 half(0.3f, 0.3f, 0.3f);
  sc.meshes = {quadMesh(4.0f, 0), boxMesh(half, 0)};
  sc.instances.push_back({0, glm::mat4(1.0f), "floor"});
  glm::mat4 t(1.0f);
  t[3] = glm::vec4(0.0f, half.y, 0.0f, 1.0f);
  sc.instances.push_back({1, t, "box"});
  sc.camera.eye = glm::vec3(0.0f, 3.0f, 1.5f);
  sc.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
  sc.camera.yfov = 1.0f;
  sc.bounds = {glm::vec3(-4, 0, -4), glm::vec3(4, 0.6f, 4)};
  auto o = hybridOptions(sc, render::RenderMode::Hybrid, 64);
  o.settings.envColor = glm::vec3(1.0f);
  o.hybrid.aoRays = 4;
  o.hybrid.aoRadius = 0.5f;
  auto session = makeSession(o);
  session->render(8);  // AO averaged over 8 frames (temporal accumulation)
  const auto ao = session->hybrid()->readAoMask();
  const auto& cam = session->sceneCamera();
  double nearSum = 0, farSum = 0;
  int nearCount = 0, farCount = 0;
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x < 64; ++x) {
      glm::vec3 o3, d;
      cameraRay(cam, 64, 64, x + 0.5f, y + 0.5f, o3, d);
      if (d.y >= 0.0f || hitBox(o3, d, glm::vec3(-half.x, 0.0f, -half.z), half * glm::vec3(1, 2, 1)) >= 0.0f)
        continue;
      const glm::vec3 p = o3 + d * (-o3.y / d.y);
      // Distance in the floor plane from the box's footprint.
      const float dx = std::max(std::abs(p.x) - half.x, 0.0f), dz = std::max(std::abs(p.z) - half.z, 0.0f);
      const float dist = std::sqrt(dx * dx + dz * dz);
      const double open = ao[y * 64 + x] / 255.0;
      if (dist > 0.02f && dist < 0.08f) {
        nearSum += open;
        ++nearCount;
      } else if (dist > 0.8f && std::abs(p.x) < 3.5f && std::abs(p.z) < 3.5f) {
        farSum += open;
        ++farCount;
      }
    }
  }
  ASSERT_GT(nearCount, 10);
  ASSERT_GT(farCount, 100);
  std::printf("AO: %.3f next to the box (%d px), %.3f in the open (%d px)\n", nearSum / nearCount, nearCount,
              farSum / farCount, farCount);
  EXPECT_LT(nearSum / nearCount, 0.85);
  EXPECT_GT(farSum / farCount, 0.97);
  expectNoValidationErrors(*session);
}

namespace {

// A temporary copy of shaders/ that the test may edit.
struct TempShaders {
  std::filesystem::path root;
  TempShaders() {
    root = std::filesystem::temp_directory_path() /
           ("wb_hybrid_shaders_" + std::to_string(::getpid()) + "_" +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::copy(shaderDir(), root, std::filesystem::copy_options::recursive);
  }
  ~TempShaders() {
    std::error_code ec;
    std::filesystem::remove_all(root, ec);
  }
  void append(const std::string& rel, const std::string& text) const {
    std::ofstream f(root / rel, std::ios::app);
    f << text;
  }
};

}  // namespace

TEST(Hybrid, SharedIncludeRebuildsRasterAndRayTracingRasterOnlyEditDoesNot) {
  TempShaders shaders;
  ShadowScene s = makeShadowScene();
  vk::ContextOptions co;
  co.validation = true;
  vk::Context ctx(co);
  shader::ShaderLibrary::Options lo;
  lo.includeRoots = {shaders.root};
  shader::ShaderLibrary library(lo);  // memory only
  render::RenderSettings settings;
  settings.width = settings.height = 32;
  render::GpuScene gpuScene(ctx, s.scene);
  render::GpuEnvironment env(ctx, render::loadEnvironmentData(settings));
  render::HybridSettings hs;
  render::HybridRenderer hybrid({ctx, library, s.scene, gpuScene, env}, settings,
                                render::RenderMode::Reflections, hs, shaders.root);
  hybrid.render(1);

  // The include graph: common.glsl reaches every hybrid program, raster.glsl only the raster one; of the
  // shared types, the scene's and the hybrid modes' reach them all, the path tracer's none.
  auto ids = [&](const std::string& rel) {
    auto v = library.programsDependingOn(std::filesystem::canonical(shaders.root / rel));
    std::sort(v.begin(), v.end());
    return v;
  };
  std::vector<shader::ShaderLibrary::ProgramId> all = {
      hybrid.program(Pass::GBuffer), hybrid.program(Pass::ShadowAo), hybrid.program(Pass::Reflection),
      hybrid.program(Pass::Composite)};
  std::sort(all.begin(), all.end());
  EXPECT_EQ(ids("hybrid/common.glsl"), all);
  EXPECT_EQ(ids("shared/scene_types.h"), all);
  EXPECT_EQ(ids("shared/hybrid_types.h"), all);
  EXPECT_TRUE(ids("shared/pathtracer_types.h").empty());
  EXPECT_TRUE(ids("shared/inspect_types.h").empty());
  EXPECT_EQ(ids("hybrid/raster.glsl"),
            std::vector<shader::ShaderLibrary::ProgramId>{hybrid.program(Pass::GBuffer)});
  EXPECT_EQ(ids("hybrid/occlusion.glsl"),
            (std::vector<shader::ShaderLibrary::ProgramId>{
                std::min(hybrid.program(Pass::ShadowAo), hybrid.program(Pass::Reflection)),
                std::max(hybrid.program(Pass::ShadowAo), hybrid.program(Pass::Reflection))}));

  live::HotReload hot(library, {shaders.root});
  hot.addRenderer(hybrid);
  hot.start();  // the watches are in place when start() returns
  auto waitForReload = [&]() -> std::optional<live::ReloadEvent> {
    // A cap for a busy machine (a 1 s reload took tens of seconds beside two busy loops), not a timing.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
    while (std::chrono::steady_clock::now() < deadline) {
      if (auto e = hot.poll()) {
        hybrid.render(1);
        hot.frameFinished();
        return e;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return std::nullopt;
  };

  const VkPipeline shadowBefore = hybrid.pipelineHandle(Pass::ShadowAo);
  const VkPipeline reflectBefore = hybrid.pipelineHandle(Pass::Reflection);
  // Real edits (an unused global changes the SPIR-V; a define alone would not, and would rebuild nothing).
  shaders.append(
      "hybrid/raster.glsl",
      "\n#ifndef WB_TEST_RASTER_EDIT\n#define WB_TEST_RASTER_EDIT\nfloat wbTestRasterEdit = 1.0;\n#endif\n");
  auto e1 = waitForReload();
  ASSERT_TRUE(e1.has_value()) << "no reload after the raster-only edit";
  EXPECT_TRUE(e1->ok) << e1->error;
  EXPECT_EQ(e1->pipelinesRebuilt, std::vector<std::string>{render::HybridRenderer::passName(Pass::GBuffer)});
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::GBuffer), 2u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::ShadowAo), 1u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::Reflection), 1u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::Composite), 1u);
  EXPECT_EQ(hybrid.pipelineHandle(Pass::ShadowAo), shadowBefore);
  EXPECT_EQ(hybrid.pipelineHandle(Pass::Reflection), reflectBefore);

  shaders.append(
      "hybrid/common.glsl",
      "\n#ifndef WB_TEST_SHARED_EDIT\n#define WB_TEST_SHARED_EDIT\nfloat wbTestSharedEdit = 1.0;\n#endif\n");
  auto e2 = waitForReload();
  ASSERT_TRUE(e2.has_value()) << "no reload after the shared edit";
  EXPECT_TRUE(e2->ok) << e2->error;
  auto rebuilt = e2->pipelinesRebuilt;
  std::sort(rebuilt.begin(), rebuilt.end());
  std::vector<std::string> expected;
  for (auto p : {Pass::GBuffer, Pass::ShadowAo, Pass::Reflection, Pass::Composite})
    expected.push_back(render::HybridRenderer::passName(p));
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(rebuilt, expected);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::GBuffer), 3u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::ShadowAo), 2u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::Reflection), 2u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::Composite), 2u);

  // A broken raster edit keeps the last good pipeline and reports file:line; the ray tracing side is
  // untouched.
  shaders.append("hybrid/raster.glsl", "\nthis is not glsl\n");
  auto e3 = waitForReload();
  ASSERT_TRUE(e3.has_value());
  EXPECT_FALSE(e3->ok);
  EXPECT_NE(e3->error.find("raster.glsl"), std::string::npos) << e3->error;
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::GBuffer), 3u);
  EXPECT_EQ(hybrid.pipelineBuilds(Pass::ShadowAo), 2u);
  hot.stop();
  hybrid.render(1);
  EXPECT_EQ(ctx.validationErrors(), 0u);
  for (const auto& m : ctx.validationMessages()) ADD_FAILURE() << "validation: " << m;
}
