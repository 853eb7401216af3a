#include "app/render_session.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "common/paths.h"
#include "shader/hash.h"
#include "sampling/environment.h"
#include "vk/driver_env.h"

namespace wb::app {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

render::EnvironmentData loadEnvironmentData(const render::RenderSettings& settings) {
  const bool isMap = !settings.envPath.empty();
  EnvironmentMap env = isMap ? loadHdrEnvironment(settings.envPath) : constantEnvironment(settings.envColor);
  render::EnvironmentData d;
  d.width = uint32_t(env.width);
  d.height = uint32_t(env.height);
  d.rgb = std::move(env.rgb);
  d.alias = std::move(env.alias);
  d.totalWeight = env.totalWeight;
  d.isMap = isMap;
  d.warnings = std::move(env.warnings);
  return d;
}

scene::SceneFeatures featuresFor(const scene::Scene& scene, const render::RenderSettings& settings) {
  std::vector<shader::Define> extra;
  for (const auto& [k, v] : settings.defines) extra.push_back({k, v});
  if (settings.generic) {
    auto f = scene::genericFeatures(static_cast<uint32_t>(scene.lights.size()));
    f.extraDefines = extra;
    return f;
  }
  const bool black = settings.envColor == glm::vec3(0.0f) || settings.envIntensity == 0.0f;
  const auto env = !settings.envPath.empty() ? scene::EnvironmentKind::Map
                   : black                   ? scene::EnvironmentKind::None
                                             : scene::EnvironmentKind::Constant;
  auto f = scene::analyzeFeatures(scene, env);
  f.extraDefines = extra;
  return f;
}

std::string shaderSourceFingerprint() {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(shaderDir(), ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec)) files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  shader::Hasher h;
  for (const auto& f : files) {
    h.add(std::filesystem::relative(f, shaderDir(), ec).string());
    h.add(shader::readFile(f).value_or(std::string()));
  }
  return h.finish().hex();
}

RenderSession::RenderSession(const SessionOptions& options) {
  auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path scenePath =
      options.scenePath.empty() ? defaultScenePath() : std::filesystem::path(options.scenePath);
  scene_ =
      options.sceneData ? *options.sceneData : scene::loadGltf(scenePath);  // before the device: fail fast
  // The loader's warnings come first: they may be the reason a later step refuses the scene (no triangles
  // when every primitive is POINTS or LINES).
  if (!options.quiet)
    for (const auto& w : scene_.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const auto envData = loadEnvironmentData(options.settings);
  if (!options.quiet)
    for (const auto& w : envData.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  const auto cacheDir = options.cacheDir.empty() ? shaderCacheDir() : options.cacheDir;
  vk::applyDriverDefaults(cacheDir);  // Mesa's shader cache under ours, llvmpipe's vector width
  vk::ContextOptions contextOptions = options.context;
  if (contextOptions.pipelineCacheDir.empty()) contextOptions.pipelineCacheDir = cacheDir.string();
  ctx_ = std::make_unique<vk::Context>(contextOptions);
  shader::ShaderLibrary::Options lo;
  lo.includeRoots = {shaderDir()};
  lo.cacheDir = cacheDir;
  library_ = std::make_unique<shader::ShaderLibrary>(lo);
  gpuScene_ = std::make_unique<render::GpuScene>(*ctx_, scene_);
  env_ = std::make_unique<render::GpuEnvironment>(*ctx_, envData);
  tracer_ = std::make_unique<render::PathTracer>(*ctx_, *library_, *gpuScene_, *env_, options.settings,
                                                 featuresFor(scene_, options.settings));
  sceneCamera_ = render::cameraFromScene(scene_.camera);
  tracer_->setCamera(sceneCamera_);
  mode_ = options.mode;
  if (mode_ != render::RenderMode::PathTrace) {
    hybrid_ = std::make_unique<render::HybridRenderer>(*ctx_, *library_, *gpuScene_, scene_, *env_,
                                                       options.settings, mode_, options.hybrid);
    hybrid_->setCamera(sceneCamera_);
  }
  setupSeconds_ = secondsSince(t0);
}

RenderSession::~RenderSession() {
  if (ctx_) vkDeviceWaitIdle(ctx_->device());
  hybrid_.reset();
  tracer_.reset();
  env_.reset();
  gpuScene_.reset();
}

double RenderSession::render(uint32_t spp) {
  auto t0 = std::chrono::steady_clock::now();
  frameSeconds_.clear();
  if (hybrid_) {
    hybrid_->resetAccumulation();
    frameSeconds_ = hybrid_->render(spp);
    return secondsSince(t0);
  }
  tracer_->resetAccumulation();
  tracer_->resetCounters();
  for (uint32_t i = 0; i < spp; ++i) {
    const auto f0 = std::chrono::steady_clock::now();
    tracer_->render(1);
    frameSeconds_.push_back(secondsSince(f0));
  }
  return secondsSince(t0);
}

eval::ImageRGBA RenderSession::image() const {
  eval::ImageRGBA img;
  img.width = tracer_->settings().width;
  img.height = tracer_->settings().height;
  img.pixels = hybrid_ ? hybrid_->readOutput() : tracer_->readAccumulation();
  for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
  return img;
}

eval::ImageRGBA RenderSession::aov(render::Aov which) const {
  eval::ImageRGBA img;
  img.width = tracer_->settings().width;
  img.height = tracer_->settings().height;
  img.pixels = tracer_->readAov(which);
  return img;
}

}  // namespace wb::app
