#include "render/path_tracer.h"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "common/half.h"
#include "common/paths.h"
#include "render/jit_warmup.h"
#include "render/sample_tables.h"

namespace wb::render {
namespace {

constexpr uint32_t kMissCount = 2;     // environment, shadow
constexpr uint32_t kMaxRecursion = 1;  // raygen traces every ray (shadow rays too: payload.glsl)

}  // namespace

CameraState cameraFromScene(const scene::Camera& camera) {
  CameraState c;
  c.view = glm::lookAt(camera.eye, camera.target, camera.up);
  c.yfov = camera.yfov;
  c.znear = camera.znear > 0.0f ? camera.znear : 0.01f;
  return c;
}

std::vector<shader::ShaderKey> PathTracer::stageKeys(const scene::SceneFeatures& features,
                                                     bool cpuDeviceCode) {
  const auto dir = shaderDir() / "pathtracer";
  auto defines = scene::featureDefines(features);
  const bool userChose = std::any_of(features.extraDefines.begin(), features.extraDefines.end(),
                                     [](const shader::Define& d) { return d.name == "WB_CPU_DEVICE"; });
  if (cpuDeviceCode && !userChose) defines.insert(defines.begin(), {"WB_CPU_DEVICE", "1"});
  std::vector<shader::ShaderKey> keys = {
      {dir / "raygen.rgen", std::nullopt, defines},
      {dir / "miss.rmiss", std::nullopt, defines},
      {dir / "shadow.rmiss", std::nullopt, defines},
      {dir / "closesthit.rchit", std::nullopt, defines},
  };
  if (features.anyAlpha()) keys.push_back({dir / "anyhit.rahit", std::nullopt, defines});
  return keys;
}

PathTracer::PathTracer(vk::Context& ctx, shader::ShaderLibrary& library, const GpuScene& scene,
                       const GpuEnvironment& env, const RenderSettings& settings,
                       const scene::SceneFeatures& features)
    : ctx_(ctx), library_(library), scene_(scene), env_(&env), settings_(settings) {
  // On GPUs by default; not on lavapipe: Mesa 25.0 links ray tracing libraries without a validation error but
  // the linked pipeline renders nothing (and it would gain nothing there: llvmpipe compiles the linked
  // pipeline as one function at its first dispatch). WB_PIPELINE_LIBRARY=0 / =1 forces it off / on.
  const char* lib = std::getenv("WB_PIPELINE_LIBRARY");
  const bool forced = lib && std::string(lib) == "1", off = lib && std::string(lib) == "0";
  if (ctx.pipelineLibrarySupported() && !off && (!ctx.cpuDevice() || forced)) {
    libraries_ = std::make_unique<vk::RtLibraryCache>(ctx);
  }
  frameUniforms_ = vk::Buffer(ctx, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  counters_ = vk::Buffer(ctx, sizeof(gpu::Counters), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  resetCounters();
  blueNoise_ = vk::makeBuffer(ctx, blueNoiseTable(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  sobol_ = vk::makeBuffer(ctx, sobolTable(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  createImages();
  {
    vk::DescriptorSets recorder(ctx);
    writeDescriptors(recorder);
    provided_ = recorder.requested();
  }
  const char* code = std::getenv("WB_CPU_DEVICE_CODE");
  cpuDeviceCode_ = code && *code ? std::string(code) == "1" : ctx.cpuDevice();
  setFeatures(features);
  warmupEnabled_ = jitWarmupWanted(ctx);
}

bool PathTracer::setFeatures(const scene::SceneFeatures& features) {
  if (pipeline_ && features == features_) return false;
  shader::ShaderLibrary::ProgramId id = 0;
  bool found = false;
  for (const auto& [f, p] : variants_) {
    if (f == features) {
      id = p;
      found = true;
    }
  }
  if (!found) {
    id = library_.registerProgram(features.generic ? "pathtracer" : "pathtracer (specialised)",
                                  stageKeys(features, cpuDeviceCode_));
    variants_.emplace_back(features, id);
  }
  swapPipeline(library_.buildProgram(id));
  program_ = id;
  features_ = features;
  return true;
}

PathTracer::~PathTracer() {
  vkDeviceWaitIdle(ctx_.device());
}

uint32_t PathTracer::jitWarmups() const {
  return warmup_.warmups();
}

void PathTracer::createImages() {
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  accum_ = vk::Image(ctx_, settings_.width, settings_.height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  albedo_ = vk::Image(ctx_, settings_.width, settings_.height, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
  normal_ = vk::Image(ctx_, settings_.width, settings_.height, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
  info_ = vk::Image(ctx_, settings_.width, settings_.height, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* img : {&accum_, &albedo_, &normal_, &info_}) {
      vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      VkClearColorValue zero{};
      VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, img->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    }
  });
  sampleIndex_ = 0;
}

void PathTracer::writeDescriptors(vk::DescriptorSets& s) {
  emitterVersion_ = scene_.emitterVersion();
  s.writeAccelerationStructure(0, WB_BIND_TLAS, scene_.tlas());
  s.writeStorageImage(0, WB_BIND_ACCUM, accum_.view());
  s.writeStorageImage(0, WB_BIND_AOV_ALBEDO, albedo_.view());
  s.writeStorageImage(0, WB_BIND_AOV_NORMAL, normal_.view());
  s.writeStorageImage(0, WB_BIND_AOV_INFO, info_.view());
  s.writeBuffer(0, WB_BIND_FRAME, frameUniforms_.handle());
  s.writeBuffer(0, WB_BIND_GEOMETRIES, scene_.geometries().handle());
  s.writeBuffer(0, WB_BIND_MATERIALS, scene_.materials().handle());
  s.writeBuffer(0, WB_BIND_LIGHTS, scene_.lights().handle());
  s.writeSampledImages(0, WB_BIND_TEXTURES, scene_.textureDescriptors());
  s.writeSampledImages(0, WB_BIND_ENV_MAP, {env_->descriptor()});
  s.writeBuffer(0, WB_BIND_ENV_ALIAS, env_->aliasTable().handle());
  s.writeBuffer(0, WB_BIND_COUNTERS, counters_.handle());
  s.writeBuffer(0, WB_BIND_BLUE_NOISE, blueNoise_.handle());
  s.writeBuffer(0, WB_BIND_SOBOL, sobol_.handle());
  s.writeBuffer(0, WB_BIND_EMITTERS, scene_.emitters().handle());
  s.writeBuffer(0, WB_BIND_EMITTER_ALIAS, scene_.emitterAlias().handle());
}

std::unique_ptr<PreparedPipeline> PathTracer::preparePipeline(
    const shader::ShaderLibrary::ProgramBuild& build) const {
  // A binding the path tracer does not fill would be read unbound (VUID-vkCmdTraceRaysKHR-None-02699): a
  // compile error at its declaration instead, and the last good pipeline stays.
  vk::requireProvided(build, provided_, "the path tracer");
  // Groups: raygen, environment miss, shadow miss, one triangle hit group (closest-hit + any-hit when the
  // program has an any-hit stage, i.e. some material is not opaque).
  const int anyHit = build.stages.size() > 4 ? 4 : -1;
  const std::vector<vk::RtShaderGroup> groups = {
      {0, -1, -1, -1}, {1, -1, -1, -1}, {2, -1, -1, -1}, {-1, 3, anyHit, -1}};
  auto prepared = std::make_unique<PreparedPipeline>();
  prepared->layout = std::make_unique<vk::PipelineLayout>(ctx_, build.layout);
  prepared->pipeline = std::make_unique<vk::RayTracingPipeline>(
      ctx_, build.stages, groups, kMissCount, prepared->layout->handle(), kMaxRecursion,
      std::vector<vk::SpecializationConstant>{}, libraries_.get(), vk::layoutKey(build.layout));
  return prepared;
}

void PathTracer::commitPipeline(std::unique_ptr<PreparedPipeline> prepared) {
  vkDeviceWaitIdle(ctx_.device());  // the old pipeline and descriptor sets may still be in flight
  sets_.reset();
  pipeline_ = std::move(prepared->pipeline);
  layout_ = std::move(prepared->layout);
  sets_ = std::make_unique<vk::DescriptorSets>(ctx_, *layout_);
  writeDescriptors(*sets_);
  pipelineMs_ = pipeline_->createMs();
  sampleIndex_ = 0;
  // Libraries of the last few builds stay (variants and an edit in flight); older ones go.
  if (libraries_) libraries_->trim(24, pipeline_->libraryKeys());
}

void PathTracer::addHotReloadTarget(HotReload& hot) {
  auto makeWarmup = [this, features = features_] {
    return std::make_unique<PathTracerJitWarmup>(ctx_, library_.options(), features);
  };
  if (warmupEnabled_) warmup_.makeAhead(makeWarmup);
  hot.addTarget(program_,
                {"pathtracer",
                 [this, makeWarmup](const shader::ShaderLibrary::ProgramBuild& b) -> std::shared_ptr<void> {
                   // Before the warm-up device sees it: a program that uses a binding we do not fill is a
                   // reload error, not a warm-up failure.
                   vk::requireProvided(b, provided_, "the path tracer");
                   // The driver's compile on the warm-up device runs beside this device's pipeline creation.
                   const uint32_t handlesBefore = ctx_.lastGroupHandleWord();
                   std::vector<uint8_t> warmedHandles;  // empty: no warm-up ran
                   auto prepared = prepareBesideWarmup(
                       warmupEnabled_, [&] { return std::shared_ptr<PreparedPipeline>(preparePipeline(b)); },
                       [&] {
                         if (auto* w = warmup_.warmOrRenew(makeWarmup, [&](PathTracerJitWarmup& x) {
                               return x.warm(b, handlesBefore);
                             }))
                           warmedHandles = w->groupHandles();
                       });
                   if (!warmedHandles.empty() && warmedHandles != prepared->pipeline->sbt().groupHandles())
                     ++warmupMismatches_;
                   return prepared;
                 },
                 [this](std::shared_ptr<void> p) {
                   auto prepared = std::static_pointer_cast<PreparedPipeline>(p);
                   commitPipeline(std::make_unique<PreparedPipeline>(std::move(*prepared)));
                 },
                 [](const std::shared_ptr<void>& p) {
                   return std::static_pointer_cast<PreparedPipeline>(p)->pipeline->libraryStats();
                 }});
}

void PathTracer::swapPipeline(const shader::ShaderLibrary::ProgramBuild& build) {
  commitPipeline(preparePipeline(build));
}

void PathTracer::setCamera(const CameraState& camera) {
  camera_ = camera;
  sampleIndex_ = 0;
}

void PathTracer::setSettings(const RenderSettings& settings) {
  const bool resized = settings.width != settings_.width || settings.height != settings_.height;
  settings_ = settings;
  if (resized) {
    vkDeviceWaitIdle(ctx_.device());
    createImages();
    writeDescriptors(*sets_);
  }
  sampleIndex_ = 0;
}

void PathTracer::setEnvironment(const GpuEnvironment& env) {
  vkDeviceWaitIdle(ctx_.device());
  env_ = &env;
  writeDescriptors(*sets_);
  sampleIndex_ = 0;
}

void PathTracer::updateFrameUniforms() {
  gpu::FrameUniforms f{};
  const float aspect = float(settings_.width) / float(settings_.height);
  glm::mat4 proj = glm::perspective(camera_.yfov, aspect, camera_.znear, 1000.0f);
  proj[1][1] *= -1.0f;  // Vulkan: row 0 of the image is the top
  f.viewInverse = glm::inverse(camera_.view);
  f.projInverse = glm::inverse(proj);
  f.envColor = glm::vec4(settings_.envColor, 1.0f);
  f.lightCount = scene_.lightCount();
  f.envMapPresent = env_->isMap() ? 1u : 0u;
  f.envWidth = env_->width();
  f.envHeight = env_->height();
  f.envIntensity = settings_.envIntensity;
  f.envRotation = glm::radians(settings_.envRotationDeg);
  f.envTotalWeight = env_->totalWeight();
  f.emitterCount = scene_.emitterCount();
  f.emitterTotalPower = scene_.emitterTotalPower();
  // Light sampling splits between the environment and the area lights; a black environment gets none.
  const bool envBlack =
      settings_.envIntensity <= 0.0f || (!env_->isMap() && settings_.envColor == glm::vec3(0.0f));
  f.envSelectProbability = f.emitterCount == 0 ? 1.0f : envBlack ? 0.0f : 0.5f;
  std::memcpy(frameUniforms_.mapped(), &f, sizeof(f));
}

void PathTracer::record(VkCommandBuffer cmd, std::optional<PixelRegion> region) {
  PixelRegion r = region.value_or(PixelRegion{0, 0, settings_.width, settings_.height});
  // A material edit rebuilt the area lights' buffers (at a frame boundary, nothing in flight): point at them.
  if (scene_.emitterVersion() != emitterVersion_) writeDescriptors(*sets_);
  if (sampleIndex_ == 0 && (!region || (r.x == 0 && r.y == 0))) updateFrameUniforms();
  gpu::PushConstants pc{};
  pc.sampleIndex = sampleIndex_;
  pc.maxBounces = settings_.maxBounces;
  pc.rrStart = settings_.rrStart;
  pc.rrMin = settings_.rrMin;
  pc.rrMax = settings_.rrMax;
  pc.flags = (settings_.sampler == SamplerKind::Pcg ? WB_FLAG_SAMPLER_PCG : 0u) |
             (settings_.nee ? 0u : WB_FLAG_NO_NEE) | (settings_.mis ? 0u : WB_FLAG_NO_BRDF_MIS) |
             (settings_.russianRoulette ? 0u : WB_FLAG_NO_RR) | (settings_.aov ? WB_FLAG_AOV : 0u);
  pc.seed = settings_.seed;
  pc.debugView = settings_.debugView;
  pc.tileOffset = glm::uvec2(r.x, r.y);
  pc.imageSize = glm::uvec2(settings_.width, settings_.height);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_->handle());
  const auto& sets = sets_->sets();
  if (!sets.empty()) {
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, layout_->handle(), 0,
                            static_cast<uint32_t>(sets.size()), sets.data(), 0, nullptr);
  }
  for (const auto& range : layout_->desc().pushConstants) {
    vkCmdPushConstants(cmd, layout_->handle(), range.stageFlags, range.offset, range.size,
                       reinterpret_cast<const char*>(&pc) + range.offset);
  }
  pipeline_->sbt().trace(ctx_, cmd, r.width, r.height);
  vk::memoryBarrier(cmd);
}

void PathTracer::render(uint32_t samples) {
  const uint32_t tw = settings_.tileWidth ? settings_.tileWidth : settings_.width;
  const uint32_t th = settings_.tileHeight ? settings_.tileHeight : settings_.height;
  for (uint32_t i = 0; i < samples; ++i) {
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
      for (uint32_t y = 0; y < settings_.height; y += th) {
        for (uint32_t x = 0; x < settings_.width; x += tw) {
          record(cmd,
                 PixelRegion{x, y, std::min(tw, settings_.width - x), std::min(th, settings_.height - y)});
        }
      }
    });
    advanceSample();
  }
}

std::vector<float> PathTracer::readAccumulation() const {
  auto bytes = accum_.download(VK_IMAGE_LAYOUT_GENERAL);
  std::vector<float> out(bytes.size() / sizeof(float));
  std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

std::vector<float> PathTracer::readAov(Aov aov) const {
  return halvesToFloats(aovImage(aov).download(VK_IMAGE_LAYOUT_GENERAL));
}

gpu::Counters PathTracer::readCounters() const {
  gpu::Counters c;
  std::memcpy(&c, counters_.mapped(), sizeof(c));
  return c;
}

void PathTracer::resetCounters() {
  std::memset(counters_.mapped(), 0, sizeof(gpu::Counters));
}

}  // namespace wb::render
