#include "render/jit_warmup.h"

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "scene/procedural.h"
#include "vk/check.h"
#include "vk/pipeline_layout.h"
#include "vk/shader_module.h"

namespace wb::render {
namespace {

constexpr int kCompiledMs = 50;  // a warm-up dispatch slower than this compiled the pipeline

// One quad, one material, a sun: every buffer the path tracer and the hybrid renderer bind exists and is
// valid.
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
  gpu::DirectionalLight sun{};
  sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  sun.cosAngularRadius = 1.0f;
  sun.radiance = glm::vec3(1.0f);
  s.lights.push_back(sun);
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

std::unique_ptr<vk::Context> warmupContext(const vk::Context& main) {
  vk::ContextOptions o;
  o.deviceName = main.deviceName();
  o.validation = main.validationEnabled();
  return std::make_unique<vk::Context>(o);
}

std::unique_ptr<shader::ShaderLibrary> warmupLibrary(shader::ShaderLibrary::Options o) {
  o.printWarnings = false;  // the main library already reports cache problems
  return std::make_unique<shader::ShaderLibrary>(o);
}

// Waits (up to 2 s) until Mesa's writer thread stored what a dispatch that took `dispatch` compiled: a cache
// load takes ~10 ms, a compile hundreds. The render device's first use then finds the entry.
void awaitCacheWrite(std::chrono::steady_clock::duration dispatch, uint64_t bytesBefore) {
  if (dispatch < std::chrono::milliseconds(kCompiledMs)) return;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (mesaShaderCacheBytes() == bytesBefore && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

}  // namespace

bool jitWarmupWanted(const vk::Context& ctx) {
  const char* v = std::getenv("WB_JIT_WARMUP");
  if (v && std::string(v) == "0") return false;
  if (v && std::string(v) == "1") return true;
  return ctx.cpuDevice();
}

bool alignGroupHandles(vk::Context& ctx, const shader::ShaderLibrary::ProgramBuild& build, uint32_t last) {
  const shader::CompiledShader* raygen = nullptr;
  for (const auto& s : build.stages)
    if (s->stage == shader::Stage::RayGen) raygen = s.get();
  if (!raygen) return true;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const uint32_t now = ctx.lastGroupHandleWord();
    if (now == last) return true;
    if (now > last) return false;
    const uint32_t count = last - now;
    vk::PipelineLayout layout(ctx, build.layout);
    const vk::ShaderModule module(ctx.device(), *raygen);
    const VkPipelineShaderStageCreateInfo stage = module.stageInfo();
    VkRayTracingShaderGroupCreateInfoKHR group{VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    group.type = VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR;
    group.generalShader = 0;
    group.closestHitShader = group.anyHitShader = group.intersectionShader = VK_SHADER_UNUSED_KHR;
    const std::vector<VkRayTracingShaderGroupCreateInfoKHR> groups(count, group);
    VkRayTracingPipelineCreateInfoKHR ci{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
    ci.stageCount = 1;
    ci.pStages = &stage;
    ci.groupCount = count;
    ci.pGroups = groups.data();
    ci.maxPipelineRayRecursionDepth = 1;
    ci.layout = layout.handle();
    VkPipeline pipeline = VK_NULL_HANDLE;
    WB_VK(ctx.vkCreateRayTracingPipelinesKHR(ctx.device(), VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &ci, nullptr,
                                             &pipeline));
    std::vector<uint8_t> handles(size_t(count) * ctx.rayTracing().handleSize);
    const VkResult h = ctx.vkGetRayTracingShaderGroupHandlesKHR(ctx.device(), pipeline, 0, count,
                                                                handles.size(), handles.data());
    vkDestroyPipeline(ctx.device(), pipeline, nullptr);
    WB_VK(h);
    ctx.noteGroupHandles(handles);
  }
  return ctx.lastGroupHandleWord() == last;
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

WarmupDevice::WarmupDevice(const vk::Context& main, const shader::ShaderLibrary::Options& libraryOptions)
    : ctx(warmupContext(main)), library(warmupLibrary(libraryOptions)), scene(standInScene()) {
  gpuScene = std::make_unique<GpuScene>(*ctx, scene);
  env = std::make_unique<GpuEnvironment>(*ctx, blackEnvironment());
  settings.width = settings.height = 1;
}

WarmupDevice::~WarmupDevice() {
  env.reset();
  gpuScene.reset();
}

PathTracerJitWarmup::PathTracerJitWarmup(const vk::Context& main,
                                         const shader::ShaderLibrary::Options& libraryOptions,
                                         const scene::SceneFeatures& features)
    : device_(main, libraryOptions) {
  tracer_ = std::make_unique<PathTracer>(*device_.ctx, *device_.library, *device_.gpuScene, *device_.env,
                                         device_.settings, features);
}

PathTracerJitWarmup::~PathTracerJitWarmup() = default;

bool PathTracerJitWarmup::warm(const shader::ShaderLibrary::ProgramBuild& build,
                               uint32_t renderDeviceGroupHandle) {
  using Clock = std::chrono::steady_clock;
  if (!alignGroupHandles(*device_.ctx, build, renderDeviceGroupHandle)) return false;
  tracer_->swapPipeline(build);
  const uint64_t before = mesaShaderCacheBytes();
  const auto t1 = Clock::now();
  // Zero rays: llvmpipe compiles the pipeline when it is dispatched, before it looks at the size.
  device_.ctx->submitAndWait([&](VkCommandBuffer cmd) { tracer_->record(cmd, PixelRegion{0, 0, 0, 0}); });
  awaitCacheWrite(Clock::now() - t1, before);
  ++warmups_;
  return true;
}

HybridJitWarmup::HybridJitWarmup(const vk::Context& main,
                                 const shader::ShaderLibrary::Options& libraryOptions, RenderMode mode,
                                 const HybridSettings& hybrid, const std::filesystem::path& shaderRoot)
    : device_(main, libraryOptions) {
  renderer_ =
      std::make_unique<HybridRenderer>(*device_.ctx, *device_.library, *device_.gpuScene, device_.scene,
                                       *device_.env, device_.settings, mode, hybrid, shaderRoot);
}

HybridJitWarmup::~HybridJitWarmup() = default;

bool HybridJitWarmup::warm(HybridRenderer::Pass pass, const shader::ShaderLibrary::ProgramBuild& build,
                           const HybridSettings& hybrid, uint32_t renderDeviceGroupHandle) {
  using Clock = std::chrono::steady_clock;
  // Settings first: a new reflection depth rebuilds the reflection pipeline (new group numbers).
  if (hybrid.reflectionDepth != renderer_->hybridSettings().reflectionDepth)
    renderer_->setHybridSettings(hybrid);
  if (!alignGroupHandles(*device_.ctx, build, renderDeviceGroupHandle)) return false;
  renderer_->commitPipeline(pass, renderer_->preparePipeline(pass, build));
  const uint64_t before = mesaShaderCacheBytes();
  const auto t1 = Clock::now();
  renderer_->render(1);  // every pass at 1x1: llvmpipe compiles the new pipeline at its first use
  awaitCacheWrite(Clock::now() - t1, before);
  ++warmups_;
  return true;
}

}  // namespace wb::render
