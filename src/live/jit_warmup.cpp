#include "live/jit_warmup.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>

#include "common/env.h"
#include "common/statistics.h"
#include "common/thread_cpu.h"
#include "scene/procedural.h"
#include "vk/check.h"
#include "vk/pipeline_layout.h"
#include "vk/shader_module.h"

namespace wb::live {
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

render::EnvironmentData blackEnvironment() {
  render::EnvironmentData d;
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

// Waits (up to 2 s) until Mesa's writer thread stored what a dispatch that took `dispatch` compiled (a
// dispatch that loaded its pipeline from the cache is an order of magnitude shorter than one that compiled).
// The render device's first use then finds the entry.
void awaitCacheWrite(std::chrono::steady_clock::duration dispatch, uint64_t bytesBefore) {
  if (dispatch < std::chrono::milliseconds(kCompiledMs)) return;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (mesaShaderCacheBytes() == bytesBefore && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

// `seconds` with `latest` added, keeping the last 16 (the limits take their median).
void remember(std::vector<double>& seconds, double latest) {
  seconds.push_back(latest);
  if (seconds.size() > 16) seconds.erase(seconds.begin());
}

const shader::CompiledShader* raygenStage(const shader::ShaderLibrary::ProgramBuild& build) {
  for (const auto& s : build.stages)
    if (s->stage == shader::Stage::RayGen) return s.get();
  return nullptr;
}

// Creates a pipeline of `count` general groups of `raygen` on `ctx` and returns the largest leading word of
// their handles (the counter's value after them).
uint32_t makeThrowawayGroups(vk::Context& ctx, const shader::ShaderLibrary::ProgramBuild& build,
                             const shader::CompiledShader& raygen, uint32_t count) {
  vk::PipelineLayout layout(ctx, build.layout);
  const vk::ShaderModule module(ctx.device(), raygen);
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
  const uint32_t handleSize = ctx.rayTracing().handleSize;
  std::vector<uint8_t> handles(size_t(count) * handleSize);
  const VkResult h = ctx.vkGetRayTracingShaderGroupHandlesKHR(ctx.device(), pipeline, 0, count,
                                                              handles.size(), handles.data());
  vkDestroyPipeline(ctx.device(), pipeline, nullptr);
  WB_VK(h);
  uint32_t last = 0;
  for (size_t at = 0; at + sizeof(uint32_t) <= handles.size(); at += std::max<size_t>(handleSize, 4)) {
    uint32_t word;
    std::memcpy(&word, handles.data() + at, sizeof word);
    last = std::max(last, word);
  }
  return last;
}

}  // namespace

std::optional<uint32_t> probeGroupCounter(vk::Context& ctx,
                                          const shader::ShaderLibrary::ProgramBuild& build) {
  const auto* raygen = raygenStage(build);
  if (!raygen) return std::nullopt;
  return makeThrowawayGroups(ctx, build, *raygen, 1);
}

bool alignGroupCounter(vk::Context& ctx, const shader::ShaderLibrary::ProgramBuild& build, uint32_t last) {
  const auto* raygen = raygenStage(build);
  if (!raygen) return true;
  const uint32_t now = makeThrowawayGroups(ctx, build, *raygen, 1);
  if (now == last) return true;
  if (now > last) return false;
  return makeThrowawayGroups(ctx, build, *raygen, last - now) == last;
}

bool warmupFrameMayStillFinish(double wall, double cpu, double limit, bool countCpu) {
  constexpr double kStarvedLimits = 20.0;
  if (wall < limit) return true;
  return countCpu && cpu < limit && wall < kStarvedLimits * limit;
}

uint64_t mesaShaderCacheBytes() {
  const auto dir = env::get("MESA_SHADER_CACHE_DIR");
  if (!dir) return 0;
  uint64_t bytes = 0;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(*dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    if (it->is_regular_file(ec)) bytes += it->file_size(ec);
  }
  return bytes;
}

WarmupDevice::WarmupDevice(const vk::Context& main, const shader::ShaderLibrary::Options& libraryOptions)
    : library(warmupLibrary(libraryOptions)), scene(standInScene()) {
  const std::vector<long> before = threadIds();
  ctx = warmupContext(main);
  gpuScene = std::make_unique<render::GpuScene>(*ctx, scene);
  env = std::make_unique<render::GpuEnvironment>(*ctx, blackEnvironment());
  driverThreads = threadsStartedSince(before, threadIds());
}

WarmupDevice::~WarmupDevice() {
  env.reset();
  gpuScene.reset();
}

render::RendererResources WarmupDevice::resources() const {
  return {*ctx, *library, scene, *gpuScene, *env};
}

JitWarmup::JitWarmup(const render::Renderer& like, const shader::ShaderLibrary::Options& libraryOptions)
    : device_(like.context(), libraryOptions) {
  render::RenderSettings settings = like.settings();
  settings.width = settings.height = kTrialSize;
  settings.tileWidth = settings.tileHeight = 0;
  settings.spp = 0;
  renderer_ = like.makeLike(device_.resources(), settings);
  // The stand-in's own camera: every pixel of the trial frame sees its quad, so hit shaders run.
  renderer_->setCamera(render::cameraFromScene(device_.scene.camera));
}

JitWarmup::~JitWarmup() = default;

WarmOutcome JitWarmup::warm(const render::Renderer& like, size_t passIndex,
                            const shader::ShaderLibrary::ProgramBuild& build,
                            std::optional<uint32_t> renderDeviceGroupCounter, bool compileAhead) {
  using Clock = std::chrono::steady_clock;
  vk::Context& ctx = *device_.ctx;
  const double hangSeconds = like.context().policy().hangSeconds;
  const bool countCpu = like.context().policy().hangCountsDriverCpu && !device_.driverThreads.empty();
  // Compiled parameters first: a new specialisation rebuilds a pipeline here (new group numbers).
  renderer_->matchCompiledParameters(like);
  if (compileAhead && !alignGroupCounter(ctx, build, renderDeviceGroupCounter.value_or(0)))
    return WarmOutcome::Renew;
  render::Pass& pass = *renderer_->passes().at(passIndex);
  auto built = pass.buildPipeline(pass.program(), build);
  const auto& rt = built.pipeline->rayTracing;
  handles_ = rt ? rt->sbt().groupHandles() : std::vector<uint8_t>{};
  pass.install(std::move(built));
  auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  if (compileAhead) {
    // The compile itself has no bound worth guessing on a busy machine (this thread and the driver's run at a
    // lowered priority: beside two busy loops a compile took over a minute), so the limit grows with the
    // compiles before it; a renderer whose compile-only record runs shaders (the hybrid modes') still ends
    // on a hang, after longer.
    const uint64_t before = mesaShaderCacheBytes();
    const auto t1 = Clock::now();
    const auto compileLimit =
        std::chrono::duration<double>(std::max({60.0, 12.0 * hangSeconds, 20.0 * median(compileSeconds_)}));
    if (!finishes([&](VkCommandBuffer cmd) { renderer_->recordCompileOnly(cmd); }, compileLimit.count(),
                  countCpu)) {
      trialLimit_ = compileLimit.count();
      return WarmOutcome::Hung;
    }
    remember(compileSeconds_, seconds(Clock::now() - t1));
    awaitCacheWrite(Clock::now() - t1, before);
  }
  if (!like.context().policy().trialRuns) {
    ++warmups_;
    return WarmOutcome::Warmed;
  }
  // The trial frame: a small image of real paths. It finishes in milliseconds; the limit is the policy's
  // floor or many times the trial frames before it, whichever is longer.
  trialLimit_ = std::max(hangSeconds, 50.0 * median(trialSeconds_));
  renderer_->resetAccumulation();
  const auto t2 = Clock::now();
  if (!finishes([&](VkCommandBuffer cmd) { renderer_->record(cmd); }, trialLimit_, countCpu))
    return WarmOutcome::Hung;
  renderer_->advance();
  remember(trialSeconds_, seconds(Clock::now() - t2));
  ++warmups_;
  return WarmOutcome::Warmed;
}

bool JitWarmup::finishes(const std::function<void(VkCommandBuffer)>& record, double limit, bool countCpu) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto cpuAtStart = countCpu ? threadCpuSeconds(device_.driverThreads) : std::map<long, double>{};
  double cpu = 0;
  const bool done = device_.ctx->submitAndWaitWhile(record, [&] {
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    if (countCpu && wall >= limit)
      cpu = cpuSecondsBetween(cpuAtStart, threadCpuSeconds(device_.driverThreads));
    return warmupFrameMayStillFinish(wall, cpu, limit, countCpu);
  });
  hangCpuSeconds_ = done || !countCpu ? -1.0 : cpu;
  return done;
}

}  // namespace wb::live
