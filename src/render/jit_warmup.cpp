#include "render/jit_warmup.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "scene/procedural.h"

namespace wb::render {
namespace {

constexpr int kCompiledMs = 50;  // a warm-up dispatch slower than this compiled the pipeline

// One quad, one material, no lights: every buffer the path tracer binds exists and is valid.
scene::Scene standInScene() {
  scene::Scene s;
  s.sourcePath = "generated:jit-warmup";
  s.materials = {scene::makeMaterial(glm::vec3(0.5f), 0.0f, 0.5f)};
  s.materialNames = {"stand-in"};
  s.meshes.push_back(scene::makeQuad(1.0f, 0));
  s.instances.push_back({0, glm::mat4(1.0f), "stand-in"});
  s.camera.eye = glm::vec3(0.0f, 1.0f, 2.0f);
  s.camera.target = glm::vec3(0.0f);
  s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
  s.bounds = {glm::vec3(-1.0f, 0.0f, -1.0f), glm::vec3(1.0f, 0.0f, 1.0f)};
  return s;
}

EnvironmentData blackEnvironment() {
  EnvironmentData d;
  d.rgb = {0.0f, 0.0f, 0.0f};
  d.alias = {gpu::EnvAliasEntry{}};
  d.alias[0].prob = 1.0f;
  d.totalWeight = 1.0f;
  return d;
}

}  // namespace

bool jitWarmupWanted(const vk::Context& ctx) {
  const char* v = std::getenv("WB_JIT_WARMUP");
  if (v && std::string(v) == "0") return false;
  if (v && std::string(v) == "1") return true;
  return ctx.cpuDevice();
}

uint64_t mesaShaderCacheBytes() {
  const char* dir = std::getenv("MESA_SHADER_CACHE_DIR");
  if (!dir || !*dir) return 0;
  uint64_t bytes = 0;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec)) bytes += it->file_size(ec);
  }
  return bytes;
}

PathTracerJitWarmup::PathTracerJitWarmup(const vk::Context& main,
                                         const shader::ShaderLibrary::Options& libraryOptions,
                                         const scene::SceneFeatures& features) {
  vk::ContextOptions o;
  o.deviceName = main.deviceName();
  o.validation = main.validationEnabled();
  ctx_ = std::make_unique<vk::Context>(o);
  auto lo = libraryOptions;
  lo.printWarnings = false;  // the main library already reports cache problems
  library_ = std::make_unique<shader::ShaderLibrary>(lo);
  scene_ = standInScene();
  gpuScene_ = std::make_unique<GpuScene>(*ctx_, scene_);
  env_ = std::make_unique<GpuEnvironment>(*ctx_, blackEnvironment());
  RenderSettings settings;
  settings.width = settings.height = 1;
  tracer_ = std::make_unique<PathTracer>(*ctx_, *library_, *gpuScene_, *env_, settings, features);
}

PathTracerJitWarmup::~PathTracerJitWarmup() {
  tracer_.reset();
  env_.reset();
  gpuScene_.reset();
}

double PathTracerJitWarmup::warm(const shader::ShaderLibrary::ProgramBuild& build) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  tracer_->swapPipeline(build);
  const uint64_t before = mesaShaderCacheBytes();
  const auto t1 = Clock::now();
  // Zero rays: llvmpipe compiles the pipeline when it is dispatched, before it looks at the size.
  ctx_->submitAndWait([&](VkCommandBuffer cmd) { tracer_->record(cmd, PixelRegion{0, 0, 0, 0}); });
  // Mesa writes cache entries on a thread of its own: when the dispatch compiled (a cache load takes ~10 ms,
  // a compile hundreds), wait until the entry is on disk so that the render device's first trace finds it.
  if (Clock::now() - t1 > std::chrono::milliseconds(kCompiledMs)) {
    const auto deadline = Clock::now() + std::chrono::seconds(2);
    while (mesaShaderCacheBytes() == before && Clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ++warmups_;
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace wb::render
