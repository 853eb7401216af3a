#include "render/render_session.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "common/paths.h"
#include "shader/hash.h"
#include "sampling/environment.h"
#include "vk/driver_policy.h"

namespace wb::render {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

EnvironmentData loadEnvironmentData(const RenderSettings& settings) {
  const bool isMap = !settings.envPath.empty();
  EnvironmentMap env = isMap ? loadHdrEnvironment(settings.envPath) : constantEnvironment(settings.envColor);
  EnvironmentData d;
  d.width = uint32_t(env.width);
  d.height = uint32_t(env.height);
  d.rgb = std::move(env.rgb);
  d.alias = std::move(env.alias);
  d.totalWeight = env.totalWeight;
  d.isMap = isMap;
  d.warnings = std::move(env.warnings);
  return d;
}

scene::SceneFeatures featuresFor(const scene::Scene& scene, const RenderSettings& settings) {
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

RenderSession::RenderSession(const SessionOptions& options)
    : mode_(options.mode), hybrid_(options.hybrid), quiet_(options.quiet) {
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
  vk::applyDriverDefaults(cacheDir);  // before the first instance of the process (vk/driver_policy.h)
  vk::ContextOptions contextOptions = options.context;
  if (contextOptions.pipelineCacheDir.empty()) contextOptions.pipelineCacheDir = cacheDir.string();
  ctx_ = std::make_unique<vk::Context>(contextOptions);
  shader::ShaderLibrary::Options lo;
  lo.includeRoots = {shaderDir()};
  lo.cacheDir = cacheDir;
  library_ = std::make_unique<shader::ShaderLibrary>(lo);
  gpuScene_ = std::make_unique<GpuScene>(*ctx_, scene_);
  env_ = std::make_unique<GpuEnvironment>(*ctx_, envData);
  lights_ = scene_.lights;
  sceneCamera_ = camera_ = cameraFromScene(scene_.camera);
  renderers_[0] = makeRenderer(RenderMode::PathTrace, options.settings);
  if (mode_ != RenderMode::PathTrace) renderers_[size_t(mode_)] = makeRenderer(mode_, options.settings);
  setupSeconds_ = secondsSince(t0);
}

RenderSession::~RenderSession() {
  for (auto& f : preparing_)
    if (f.valid()) f.wait();
  if (ctx_) ctx_->waitIdle();
  for (auto& r : renderers_) r.reset();
  env_.reset();
  gpuScene_.reset();
}

RendererResources RenderSession::resources() const {
  return {*ctx_, *library_, scene_, *gpuScene_, *env_};
}

std::unique_ptr<Renderer> RenderSession::constructRenderer(RenderMode mode, const RenderSettings& settings,
                                                           const HybridSettings& hybrid) const {
  if (mode == RenderMode::PathTrace)
    return std::make_unique<PathTracer>(resources(), settings, featuresFor(scene_, settings));
  return std::make_unique<HybridRenderer>(resources(), settings, mode, hybrid);
}

void RenderSession::adopt(Renderer& r) {
  r.setCamera(camera_);
  r.setLights(lights_);
  if (hooks_.adopted) hooks_.adopted(r);
}

std::unique_ptr<Renderer> RenderSession::makeRenderer(RenderMode mode, const RenderSettings& settings) {
  auto r = constructRenderer(mode, settings, hybrid_);
  adopt(*r);
  return r;
}

void RenderSession::prepareMode(RenderMode mode, const RenderSettings& settings) {
  const size_t m = size_t(mode);
  if (renderers_[m] || preparing_[m].valid()) return;
  preparing_[m] =
      std::async(std::launch::async, [this, mode, settings, hybrid = hybrid_, prepare = hooks_.prepare] {
        auto r = constructRenderer(mode, settings, hybrid);
        if (prepare) {
          try {
            prepare(*r);
          } catch (const std::exception& e) {
            if (!quiet_)
              std::fprintf(stderr, "warning: preparing %s off the render loop: %s\n", renderModeName(mode),
                           e.what());
          }
        }
        return r;
      });
}

bool RenderSession::modeReady(RenderMode mode) {
  const size_t m = size_t(mode);
  if (renderers_[m]) return true;
  auto& f = preparing_[m];
  if (!f.valid() || f.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
  renderers_[m] = f.get();
  adopt(*renderers_[m]);
  return true;
}

void RenderSession::finishPreparing() {
  for (size_t m = 0; m < preparing_.size(); ++m) {
    if (!preparing_[m].valid()) continue;
    preparing_[m].wait();
    modeReady(RenderMode(m));
  }
}

Renderer& RenderSession::setMode(RenderMode mode, const RenderSettings& settings) {
  auto& slot = renderers_[size_t(mode)];
  if (!slot && preparing_[size_t(mode)].valid()) {
    preparing_[size_t(mode)].wait();
    modeReady(mode);
  }
  if (!slot) slot = makeRenderer(mode, settings);
  mode_ = mode;
  return *slot;
}

void RenderSession::forEachRenderer(const std::function<void(Renderer&)>& f) {
  for (auto& r : renderers_)
    if (r) f(*r);
}

HybridRenderer* RenderSession::hybrid() {
  return mode_ == RenderMode::PathTrace ? nullptr
                                        : static_cast<HybridRenderer*>(renderers_[size_t(mode_)].get());
}

void RenderSession::setCamera(const CameraState& camera) {
  camera_ = camera;
  forEachRenderer([&](Renderer& r) { r.setCamera(camera); });
}

void RenderSession::setEnvironment(const RenderSettings& settings) {
  const auto data = loadEnvironmentData(settings);
  if (!quiet_)
    for (const auto& w : data.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  auto env = std::make_unique<GpuEnvironment>(*ctx_, data);
  finishPreparing();  // a renderer being made points at the current environment
  forEachRenderer([&](Renderer& r) { r.setEnvironment(*env); });  // each waits for the device
  env_ = std::move(env);                                          // the previous one is no longer referenced
}

void RenderSession::setLights(const std::vector<gpu::DirectionalLight>& lights) {
  finishPreparing();  // a renderer being made gets the lights when it is taken
  lights_ = lights;
  forEachRenderer([&](Renderer& r) { r.setLights(lights); });
}

void RenderSession::setHybridSettings(const HybridSettings& hybrid) {
  finishPreparing();
  hybrid_ = hybrid;
  for (size_t m = 1; m < renderers_.size(); ++m)
    if (renderers_[m]) static_cast<HybridRenderer&>(*renderers_[m]).setHybridSettings(hybrid);
}

void RenderSession::setRendererHooks(RendererHooks hooks) {
  finishPreparing();  // a renderer being made may use the hooks set so far
  hooks_ = std::move(hooks);
  if (hooks_.adopted) forEachRenderer([&](Renderer& r) { hooks_.adopted(r); });
}

double RenderSession::render(uint32_t spp, const Renderer::Progress& progress) {
  auto t0 = std::chrono::steady_clock::now();
  Renderer& r = renderer();
  r.resetAccumulation();
  r.resetCounters();
  if (vk::GpuTimer* timer = r.passTimer()) timer->resetTotals();  // the render's own per-pass times
  frameSeconds_ = r.render(spp, progress);
  return secondsSince(t0);
}

eval::ImageRGBA RenderSession::aov(Aov which) const {
  eval::ImageRGBA img;
  img.width = pathTracer().settings().width;
  img.height = pathTracer().settings().height;
  img.pixels = pathTracer().readAov(which);
  return img;
}

}  // namespace wb::render
