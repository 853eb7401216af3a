#include "render/path_tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <glm/gtc/matrix_transform.hpp>

#include "common/half.h"
#include "common/paths.h"
#include "render/sample_tables.h"
#include "shader/debug_labels.h"

namespace wb::render {
namespace {

constexpr uint32_t kMaxRecursion = 1;             // raygen traces every ray (shadow rays too: payload.glsl)
constexpr uint32_t kDefaultAssertRecords = 1024;  // the asserts variant's first failures kept
constexpr size_t kSpareSets = 2;                  // image sets of earlier sizes kept for reuse
// The split's shadow requests (splitsShadows): at most DevicePolicy::splitSlotsLimit per sample (18: 9
// vertices of 2 light samples, the default 8 bounces), in at most an eighth of the device's largest memory
// heap and 2 GiB; a sample's requests beyond its slots are traced in raygen's own loop.
constexpr VkDeviceSize kMaxSplitBytes = VkDeviceSize(2) << 30;
constexpr VkDeviceSize kSplitRequestBytes = 3 * sizeof(glm::vec4);

VkDeviceSize largestHeap(VkPhysicalDevice physical) {
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(physical, &memory);
  VkDeviceSize largest = 0;
  for (uint32_t i = 0; i < memory.memoryHeapCount; ++i)
    largest = std::max(largest, memory.memoryHeaps[i].size);
  return largest;
}

}  // namespace

bool PathTracer::isolatesLanes(bool inspect, const Instrumentation& instrumentation, uint32_t clock,
                               bool isolateLanes) {
  return isolateLanes && instrumentation.cost && !instrumentation.asserts && !inspect &&
         clock != WB_CLOCK_NONE;
}

uint32_t PathTracer::clockOf(const vk::Context& ctx) {
  return ctx.shaderClock().subgroup ? WB_CLOCK_SUBGROUP
         : ctx.shaderClock().device ? WB_CLOCK_DEVICE
                                    : WB_CLOCK_NONE;
}

std::vector<shader::ShaderKey> PathTracer::stageKeys(const scene::SceneFeatures& features, bool cpuDeviceCode,
                                                     bool inspect, const Instrumentation& instrumentation,
                                                     uint32_t clock, bool isolateLanes) {
  const auto dir = shaderDir() / "pathtracer";
  auto defines = scene::featureDefines(features);
  const bool userChose = std::any_of(features.extraDefines.begin(), features.extraDefines.end(),
                                     [](const shader::Define& d) { return d.name == "WB_CPU_DEVICE"; });
  if (cpuDeviceCode && !userChose) defines.insert(defines.begin(), {"WB_CPU_DEVICE", "1"});
  if (inspect) defines.push_back({"WB_INSPECT", "1"});
  if (instrumentation.cost) defines.push_back({"WB_COST", "1"});
  if (instrumentation.asserts) defines.push_back({"WB_ASSERTS", "1"});
  if ((inspect || instrumentation.cost) && clock != WB_CLOCK_NONE) {
    defines.push_back({"WB_CLOCK", std::to_string(clock)});
    if (isolatesLanes(inspect, instrumentation, clock, isolateLanes))
      defines.push_back({"WB_COST_ISOLATE", "1"});
  }
  std::vector<shader::ShaderKey> keys = {
      {dir / "raygen.rgen", std::nullopt, defines},
      {dir / "miss.rmiss", std::nullopt, defines},
      {dir / "shadow.rmiss", std::nullopt, defines},
      {dir / "closesthit.rchit", std::nullopt, defines},
  };
  if (features.anyAlpha()) keys.push_back({dir / "anyhit.rahit", std::nullopt, defines});
  return keys;
}

PathTracer::PathTracer(const RendererResources& r, const RenderSettings& settings,
                       const scene::SceneFeatures& features)
    : ctx_(r.ctx),
      library_(r.library),
      gpuScene_(r.gpuScene),
      env_(&r.environment),
      settings_(settings),
      cpuDeviceCode_(r.ctx.policy().cpuShapedShaderCode),
      clock_(clockOf(r.ctx)) {
  if (ctx_.policy().pipelineLibraries) libraries_ = std::make_unique<vk::RtLibraryCache>(ctx_);
  RayTracingRecipe recipe;
  // The any-hit stage is there when some material is not opaque (stageKeys).
  recipe.table.raygen("raygen.rgen")
      .miss("miss.rmiss")
      .miss("shadow.rmiss")
      .hitGroup({.closestHit = "closesthit.rchit", .anyHit = "anyhit.rahit"});
  recipe.maxRecursion = kMaxRecursion;
  recipe.libraries = libraries_.get();
  pass_ = std::make_unique<Pass>(ctx_, library_, "pathtracer", std::move(recipe));
  pass_->setPushConstantBytes(sizeof(gpu::PushConstants));
  pass_->setOnInstall([this] { sampleIndex_ = 0; });
  timer_ = std::make_unique<vk::GpuTimer>(ctx_);
  resolve_ = std::make_unique<Pass>(ctx_, library_, "pathtracer resolve", ComputeRecipe{});
  resolve_->setPushConstantBytes(sizeof(gpu::ResolveConstants));
  resolve_->useProgram("pathtracer resolve", {{shaderDir() / "pathtracer" / "resolve.comp"}});
  sampleSlots_ = vk::Buffer(ctx_, sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  frameUniforms_ = vk::Buffer(ctx_, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  counters_ = vk::Buffer(ctx_, sizeof(gpu::Counters),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  resetCounters();
  blueNoise_ = vk::makeBuffer(ctx_, blueNoiseTable(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  sobol_ = vk::makeBuffer(ctx_, sobolTable(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  lights_ = r.scene.lights;
  lightBuffer_ = vk::Buffer(ctx_, std::max<size_t>(1, lights_.size()) * sizeof(gpu::DirectionalLight),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  const auto shaded = scene::withSunAngle(lights_, settings_.sunAngleDeg);
  if (!shaded.empty())
    std::memcpy(lightBuffer_.mapped(), shaded.data(), shaded.size() * sizeof(gpu::DirectionalLight));
  createImages();
  createInspectBuffers();
  createAssertBuffers(kDefaultAssertRecords);
  if (ctx_.policy().splitShadows) {
    // Made once for the tracer's life, used by the variants that split (splitsShadows): passes() keeps one
    // layout, which the live-edit loop's records of passes and the A/B stand-ins rely on.
    RayTracingRecipe shadows;
    // Shadow rays only: miss index MISS_SHADOW, any-hit where some material is not opaque, an empty
    // closest-hit (shadow_split.rchit says why).
    shadows.table.raygen("shadow_split.rgen")
        .miss("shadow.rmiss")
        .miss("shadow.rmiss")
        .hitGroup({.closestHit = "shadow_split.rchit", .anyHit = "anyhit.rahit"});
    shadows.maxRecursion = kMaxRecursion;
    shadowPass_ = std::make_unique<Pass>(ctx_, library_, "pathtracer shadows", std::move(shadows));
    shadowPass_->setPushConstantBytes(sizeof(gpu::PushConstants));
  }
  createSplitBuffers();
  bindResources();
  resolve_->rebuild();
  setFeatures(features);
  makeDenoiser();
}

void PathTracer::makeDenoiser() {
  if (!settings_.denoise || denoiser_) return;
  denoiser_ = std::make_unique<Denoiser>(ctx_, library_);
  bindResources();
}

std::vector<Pass*> PathTracer::passes() const {
  std::vector<Pass*> out{pass_.get()};
  if (shadowPass_) out.push_back(shadowPass_.get());
  if (denoiser_)
    for (Pass* p : denoiser_->passes()) out.push_back(p);
  return out;
}

void PathTracer::recordDenoise(VkCommandBuffer cmd, uint32_t rows, vk::GpuTimer* perPass) const {
  if (denoiser_) denoiser_->record(cmd, rows, perPass);
}

void PathTracer::recordCompileOnly(VkCommandBuffer cmd) {
  recordRegion(cmd, PixelRegion{});
  if (denoiser_) denoiser_->recordCompileOnly(cmd);
}

bool PathTracer::setFeatures(const scene::SceneFeatures& features) {
  if (featuresSet_ && features == features_) return false;
  useVariant(features, inspectVariant_);
  return true;
}

void PathTracer::useVariant(const scene::SceneFeatures& features, bool inspect) {
  std::string name = features.generic ? "pathtracer" : "pathtracer (specialised)";
  if (inspect) name += " (inspect)";
  if (instrumentation_.cost) name += " (cost)";
  if (instrumentation_.asserts) name += " (asserts)";
  auto keys =
      stageKeys(features, cpuDeviceCode_, inspect, instrumentation_, clock_, ctx_.policy().costIsolatesLanes);
  split_ = splitWanted(inspect);
  splitAovs_ = split_ && (settings_.aov || settings_.denoise);
  // Shader execution reordering in the plain variants' path rays (raygen only): the measuring variants keep
  // their invocations where they are (lane isolation, one inspected pixel's records). A --define of
  // WB_INVOCATION_REORDER (its hint's form, raygen.rgen) stands where the policy allows reordering, and is
  // made 0 where it does not (the device lacks the extension, or a measuring variant).
  reorder_ =
      ctx_.policy().invocationReorder && !inspect && !instrumentation_.cost && !instrumentation_.asserts;
  auto& raygenDefines = keys[0].defines;
  const auto user = std::find_if(raygenDefines.begin(), raygenDefines.end(),
                                 [](const shader::Define& d) { return d.name == "WB_INVOCATION_REORDER"; });
  if (user == raygenDefines.end()) {
    if (reorder_) raygenDefines.push_back({"WB_INVOCATION_REORDER", "1"});
  } else if (!reorder_) {
    user->value = "0";
  } else {
    reorder_ = user->value != "0";
  }
  if (reorder_) name += " (reordered)";
  if (split_) {
    name += splitAovs_ ? " (split, AOVs)" : " (split)";
    for (auto& k : keys) k.defines.push_back({"WB_SPLIT_SHADOWS", "1"});
    if (splitAovs_)
      for (auto& k : keys) k.defines.push_back({"WB_SPLIT_AOVS", "1"});
  }
  pass_->useProgram(name, keys);
  features_ = features;
  featuresSet_ = true;
  inspectVariant_ = inspect;
  createSplitBuffers();
  if (shadowPass_) {
    // The plain variant's stages (the only one that splits): the program follows the scene's features alone.
    const auto plain = stageKeys(features, cpuDeviceCode_);
    std::vector<shader::ShaderKey> shadowKeys = {
        {shaderDir() / "pathtracer" / "shadow_split.rgen", std::nullopt, plain[0].defines},
        plain[2],
        {shaderDir() / "pathtracer" / "shadow_split.rchit", std::nullopt, plain[0].defines}};
    if (plain.size() > 4) shadowKeys.push_back(plain[4]);  // any-hit
    if (splitAovs_)
      for (auto& k : shadowKeys) k.defines.push_back({"WB_SPLIT_AOVS", "1"});
    if (shadowPass_->useProgram(features.generic ? "pathtracer shadows" : "pathtracer shadows (specialised)",
                                shadowKeys))
      shadowPass_->rebuild();
  }
  pass_->rebuild();
}

bool PathTracer::splitWanted(bool inspect) const {
  return shadowPass_ && !inspect && !instrumentation_.cost && !instrumentation_.asserts;
}

void PathTracer::createSplitBuffers() {
  // One record per pixel and sample of a launch; the slots per sample that fit the budget.
  const VkDeviceSize samples =
      split_ ? VkDeviceSize(settings_.width) * settings_.height * samplesPerLaunch() : 1;
  const VkDeviceSize budget = std::min(kMaxSplitBytes, largestHeap(ctx_.physicalDevice()) / 8);
  splitSlots_ = split_ ? uint32_t(std::min<VkDeviceSize>(ctx_.policy().splitSlotsLimit,
                                                         budget / (samples * kSplitRequestBytes)))
                       : 0;
  const VkDeviceSize requests = std::max<VkDeviceSize>(1, samples * splitSlots_) * kSplitRequestBytes;
  // A sample's record: its radiance and requests, with AOVs (one sample per launch) also theirs.
  const VkDeviceSize paths = samples * sizeof(glm::vec4) * (splitAovs_ ? WB_SPLIT_PATH_VEC4S_AOV : 1);
  if (splitRequests_.size() == requests && splitPaths_.size() == paths) return;
  ctx_.waitIdle();
  splitRequests_ = vk::Buffer(ctx_, requests, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  splitPaths_ = vk::Buffer(ctx_, paths, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
  bindResources();
}

bool PathTracer::setInspection(const std::optional<InspectRequest>& request) {
  ctx_.waitIdle();  // the buffers and descriptor sets may be in flight
  inspection_ = request;
  createInspectBuffers();
  bindResources();
  // The same variant goes on accumulating (the records start with the next sample traced); another variant
  // restarts with its install.
  if (request.has_value() == inspectVariant_) return false;
  useVariant(features_, request.has_value());
  return true;
}

bool PathTracer::setInstrumentation(const Instrumentation& instrumentation) {
  if (instrumentation == instrumentation_) return false;
  ctx_.waitIdle();
  instrumentation_ = instrumentation;
  sampleIndex_ = 0;
  useVariant(features_, inspectVariant_);
  return true;
}

void PathTracer::setAssertCapacity(uint32_t records) {
  ctx_.waitIdle();  // the buffers may be in flight
  createAssertBuffers(std::max(records, 1u));
  bindResources();
}

void PathTracer::createAssertBuffers(uint32_t records) {
  assertHeader_ = vk::Buffer(ctx_, sizeof(gpu::AssertHeader),
                             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  assertRecords_ = vk::Buffer(ctx_, VkDeviceSize(records) * sizeof(gpu::AssertRecord),
                              VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  gpu::AssertHeader h{};
  h.capacity = records;
  std::memcpy(assertHeader_.mapped(), &h, sizeof(h));
  std::memset(assertRecords_.mapped(), 0, size_t(records) * sizeof(gpu::AssertRecord));
}

AssertReport PathTracer::readAsserts() const {
  gpu::AssertHeader h{};
  std::memcpy(&h, assertHeader_.mapped(), sizeof(h));
  AssertReport r;
  r.failures = h.failures;
  r.records.resize(std::min(h.failures, h.capacity));
  if (!r.records.empty())  // memcpy's pointers must not be null, even for zero bytes
    std::memcpy(r.records.data(), assertRecords_.mapped(), r.records.size() * sizeof(gpu::AssertRecord));
  return r;
}

std::map<uint32_t, std::string> PathTracer::debugLabels() const {
  std::vector<std::filesystem::path> files;
  for (const auto& stage : pass_->installed().build.stages)
    if (stage) files.insert(files.end(), stage->files.begin(), stage->files.end());
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return shader::debugLabelsOf(files);
}

void PathTracer::createInspectBuffers() {
  // Without a request: one empty slot, so the descriptors always point at a buffer (capacity 0 records
  // nothing).
  uint32_t samples = 1, vertices = 1;
  if (inspection_) {
    samples = std::clamp(inspection_->samples, 1u, kMaxInspectSamples);
    vertices = inspection_->vertices ? inspection_->vertices : settings_.maxBounces + 1;
    vertices = std::clamp(vertices, 1u, kMaxInspectVertices);
  }
  const VkDeviceSize vertexBytes = VkDeviceSize(samples) * vertices * sizeof(gpu::InspectVertex);
  if (vertexBytes > (VkDeviceSize(256) << 20)) {
    throw std::invalid_argument("path inspector: " + std::to_string(samples) + " samples of " +
                                std::to_string(vertices) + " vertices need more than 256 MiB of records");
  }
  inspectHeader_ = vk::Buffer(ctx_, sizeof(gpu::InspectHeader), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  inspectSamples_ = vk::Buffer(ctx_, samples * sizeof(gpu::InspectSample),
                               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  inspectVertices_ = vk::Buffer(ctx_, vertexBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  const size_t printBytes = size_t(samples) * WB_PRINTS_PER_SAMPLE * sizeof(gpu::PrintRecord);
  inspectPrints_ = vk::Buffer(ctx_, printBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  std::memset(inspectPrints_.mapped(), 0, printBytes);
  gpu::InspectHeader h{};
  if (inspection_) {
    h.pixel = glm::uvec2(inspection_->x, inspection_->y);
    h.mode = inspection_->ring ? WB_INSPECT_RING : WB_INSPECT_FIRST;
    h.sampleCapacity = samples;
  }
  h.vertexCapacity = vertices;
  h.clock = clock_;
  std::memcpy(inspectHeader_.mapped(), &h, sizeof(h));
  std::memset(inspectSamples_.mapped(), 0xff, samples * sizeof(gpu::InspectSample));  // WB_INSPECT_NO_SAMPLE
  std::memset(inspectVertices_.mapped(), 0, vertexBytes);
  lastRecordedSample_ = 0;
}

InspectBuffers PathTracer::readInspection() const {
  InspectBuffers b;
  std::memcpy(&b.header, inspectHeader_.mapped(), sizeof(b.header));
  b.samples.resize(inspectSamples_.size() / sizeof(gpu::InspectSample));
  std::memcpy(b.samples.data(), inspectSamples_.mapped(), b.samples.size() * sizeof(gpu::InspectSample));
  b.vertices.resize(inspectVertices_.size() / sizeof(gpu::InspectVertex));
  std::memcpy(b.vertices.data(), inspectVertices_.mapped(), b.vertices.size() * sizeof(gpu::InspectVertex));
  b.prints.resize(inspectPrints_.size() / sizeof(gpu::PrintRecord));
  std::memcpy(b.prints.data(), inspectPrints_.mapped(), b.prints.size() * sizeof(gpu::PrintRecord));
  if (b.header.sampleCapacity == 0) b.samples.clear();
  return b;
}

PathTracer::~PathTracer() {
  ctx_.waitIdle();
}

void PathTracer::parkAccumulation(ParkSlot slot, uint32_t samples) {
  ctx_.waitIdle();
  parked_[size_t(slot)] = ParkedSet{takeImages(), samples};
  createImages();
  bindResources();
}

bool PathTracer::unparkAccumulation(ParkSlot slot) {
  auto& parked = parked_[size_t(slot)];
  if (!parked) return false;
  ctx_.waitIdle();
  spareImages_.insert(spareImages_.begin(), takeImages());
  if (spareImages_.size() > kSpareSets) spareImages_.pop_back();
  putImages(std::move(parked->images));
  sampleIndex_ = parked->samples;
  parked.reset();
  settings_.width = accum_.width();
  settings_.height = accum_.height();
  bindResources();
  return true;
}

PathTracer::ImageSet PathTracer::takeImages() {
  return ImageSet{std::move(accum_), std::move(albedo_), std::move(normal_),
                  std::move(info_),  std::move(stats_),  std::move(cost_)};
}

void PathTracer::putImages(ImageSet&& set) {
  accum_ = std::move(set.accum);
  albedo_ = std::move(set.albedo);
  normal_ = std::move(set.normal);
  info_ = std::move(set.info);
  stats_ = std::move(set.stats);
  cost_ = std::move(set.cost);
}

void PathTracer::moveParkedAccumulation(ParkSlot from, ParkSlot to) {
  if (from == to) return;
  parked_[size_t(to)] = std::move(parked_[size_t(from)]);
  parked_[size_t(from)].reset();
}

void PathTracer::createImages() {
  const uint32_t w = settings_.width, h = settings_.height;
  ImageSet current = takeImages();
  auto spare = std::find_if(spareImages_.begin(), spareImages_.end(),
                            [&](const ImageSet& s) { return s.accum.width() == w && s.accum.height() == h; });
  const bool fresh = spare == spareImages_.end();
  if (!fresh) {
    putImages(std::move(*spare));
    spareImages_.erase(spare);
  } else {
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    accum_ = vk::Image(ctx_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
    albedo_ = vk::Image(ctx_, w, h, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
    normal_ = vk::Image(ctx_, w, h, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
    info_ = vk::Image(ctx_, w, h, VK_FORMAT_R16G16B16A16_SFLOAT, usage);
    stats_ = vk::Image(ctx_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
    cost_ = vk::Image(ctx_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
    ++imageSetsAllocated_;
  }
  if (current.accum.handle()) {
    spareImages_.insert(spareImages_.begin(), std::move(current));  // the most recent first
    if (spareImages_.size() > kSpareSets) spareImages_.pop_back();
  }
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* img : {&accum_, &albedo_, &normal_, &info_, &stats_, &cost_}) {
      if (fresh) vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      VkClearColorValue zero{};
      VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, img->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    }
  });
  sampleIndex_ = 0;
}

void PathTracer::bindSharedResources(Pass& p) const {
  bindSceneResources(p, gpuScene_, *env_);
  p.setBuffer("LightBlock", lightBuffer_);  // the scene's lights with the sun's angle applied
  p.setStorageImage("accumImage", accum_.view());
  p.setBuffer("FrameBlock", frameUniforms_);
  p.setBuffer("CounterBlock", counters_);
  p.setBuffer("BlueNoiseBlock", blueNoise_);
  p.setBuffer("SobolBlock", sobol_);
  p.setBuffer("SampleSlotBlock", sampleSlots_);
  p.setBuffer("SplitRequestBlock", splitRequests_);
  p.setBuffer("SplitPathBlock", splitPaths_);
  p.setStorageImage("albedoImage", albedo_.view());  // the AOVs: accumulate.glsl
  p.setStorageImage("normalImage", normal_.view());
  p.setStorageImage("infoImage", info_.view());
  p.setStorageImage("statsImage", stats_.view());
}

void PathTracer::bindResources() {
  Pass& p = *pass_;
  emitterVersion_ = gpuScene_.emitterVersion();
  bindSharedResources(p);
  if (shadowPass_) bindSharedResources(*shadowPass_);
  p.setStorageImage("costImage", cost_.view());  // the cost variant's
  // Used by the WB_INSPECT variant only (the others' layouts skip them).
  p.setBuffer("InspectHeaderBlock", inspectHeader_);
  p.setBuffer("InspectSampleBlock", inspectSamples_);
  p.setBuffer("InspectVertexBlock", inspectVertices_);
  p.setBuffer("InspectPrintBlock", inspectPrints_);
  // Used by the WB_ASSERTS variant only.
  p.setBuffer("AssertHeaderBlock", assertHeader_);
  p.setBuffer("AssertRecordBlock", assertRecords_);
  if (denoiser_) {
    denoiser_->resize(settings_.width, settings_.height);
    denoiser_->setInputs({accum_.view(), albedo_.view(), normal_.view(), stats_.view()});
  }
  resolve_->setStorageImage("accumImage", accum_.view());
  resolve_->setBuffer("SampleSlotBlock", sampleSlots_);
}

std::unique_ptr<Renderer> PathTracer::makeLike(const RendererResources& resources,
                                               const RenderSettings& settings) const {
  return std::make_unique<PathTracer>(resources, settings, features_);
}

void PathTracer::setCamera(const CameraState& camera) {
  camera_ = camera;
  sampleIndex_ = 0;
}

void PathTracer::setSettings(const RenderSettings& settings) {
  const bool resized = settings.width != settings_.width || settings.height != settings_.height;
  // The inspector's vertex records follow max bounces unless the request sized them.
  const bool inspectResized =
      inspection_ && inspection_->vertices == 0 && settings.maxBounces != settings_.maxBounces;
  const bool sunChanged = settings.sunAngleDeg != settings_.sunAngleDeg;
  // Denoising filters the accumulation without changing it: turning it on or off restarts nothing, unless
  // the AOVs it reads were not being written. Any other call restarts accumulation, unchanged settings too
  // (the A/B comparison restarts each run that way).
  RenderSettings sameDenoise = settings;
  sameDenoise.denoise = settings_.denoise;
  const bool onlyDenoise = settings.denoise != settings_.denoise && sameDenoise == settings_;
  const bool aovsWritten = settings_.aov || settings_.denoise;
  settings_ = settings;
  makeDenoiser();
  // The split's variant without AOVs cannot write them: one that writes them is installed when they are
  // wanted (the accumulation restarts then anyway: they were not written), and kept when they no longer are,
  // so that turning the denoiser off keeps the accumulation.
  const bool splitLacksAovs = split_ && !splitAovs_ && (settings_.aov || settings_.denoise);
  if (featuresSet_ && (splitWanted(inspectVariant_) != split_ || splitLacksAovs)) {
    useVariant(features_, inspectVariant_);  // its install restarts the accumulation
    return;
  }
  if (onlyDenoise) {
    if (!aovsWritten) sampleIndex_ = 0;
    createSplitBuffers();  // the samples per launch follow the AOVs (one while they are written)
    return;
  }
  if (sunChanged) uploadLights();
  if (resized || inspectResized) {
    ctx_.waitIdle();
    if (resized) createImages();
    if (inspectResized) createInspectBuffers();
    bindResources();
  }
  createSplitBuffers();  // the size or the samples per launch may have changed
  sampleIndex_ = 0;
}

void PathTracer::setEnvironment(const GpuEnvironment& env) {
  ctx_.waitIdle();
  env_ = &env;
  bindResources();
  sampleIndex_ = 0;
}

void PathTracer::setLights(const std::vector<gpu::DirectionalLight>& lights) {
  // The count stays the scene's (the specialised shaders' WB_LIGHT_COUNT): the first ones are replaced.
  std::copy_n(lights.begin(), std::min(lights.size(), lights_.size()), lights_.begin());
  uploadLights();
  sampleIndex_ = 0;
}

void PathTracer::uploadLights() {
  const auto shaded = scene::withSunAngle(lights_, settings_.sunAngleDeg);
  const size_t bytes = shaded.size() * sizeof(gpu::DirectionalLight);
  if (bytes == 0 || std::memcmp(lightBuffer_.mapped(), shaded.data(), bytes) == 0) return;
  ctx_.waitIdle();  // a trace in flight may read the buffer
  std::memcpy(lightBuffer_.mapped(), shaded.data(), bytes);
}

void PathTracer::updateFrameUniforms() {
  gpu::FrameUniforms f{};
  const float aspect = float(settings_.width) / float(settings_.height);
  glm::mat4 proj = glm::perspective(camera_.yfov, aspect, camera_.znear, 1000.0f);
  proj[1][1] *= -1.0f;  // Vulkan: row 0 of the image is the top
  f.viewInverse = glm::inverse(camera_.view);
  f.projInverse = glm::inverse(proj);
  f.envColor = glm::vec4(settings_.envColor, 1.0f);
  f.lightCount = gpuScene_.lightCount();
  f.envMapPresent = env_->isMap() ? 1u : 0u;
  f.envWidth = env_->width();
  f.envHeight = env_->height();
  f.envIntensity = settings_.envIntensity;
  f.envRotation = glm::radians(settings_.envRotationDeg);
  f.envTotalWeight = env_->totalWeight();
  f.emitterCount = gpuScene_.emitterCount();
  f.emitterTotalPower = gpuScene_.emitterTotalPower();
  f.reflectorCount = gpuScene_.reflectorCount();
  // Light sampling splits between the environment and the area lights; a black environment gets none.
  const bool envBlack =
      settings_.envIntensity <= 0.0f || (!env_->isMap() && settings_.envColor == glm::vec3(0.0f));
  f.envSelectProbability = f.emitterCount == 0 ? 1.0f : envBlack ? 0.0f : 0.5f;
  std::memcpy(frameUniforms_.mapped(), &f, sizeof(f));
}

uint32_t PathTracer::samplesPerLaunch() const {
  // The AOVs, the inspector's records and the cost variant's image are read and written per sample by raygen
  // (samples of one launch would race on them); the asserts variant records its first failures in sample
  // order. Only the radiance has the resolve pass.
  if (settings_.aov || settings_.denoise || inspection_ || instrumentation_.cost ||
      instrumentation_.asserts || settings_.tileWidth || settings_.tileHeight)
    return 1;
  if (settings_.samplesPerLaunch != 0) return settings_.samplesPerLaunch;
  if (ctx_.policy().compilesAtFirstDispatch) return 1;
  const uint64_t pixels = uint64_t(settings_.width) * settings_.height;
  return uint32_t(std::clamp<uint64_t>(((uint64_t(1) << 20) + pixels - 1) / pixels, 1, 16));
}

uint32_t PathTracer::recordBatch(VkCommandBuffer cmd, uint32_t samples) {
  const uint32_t n = std::min(samplesPerLaunch(), std::max(samples, 1u));
  if (n <= 1) {
    record(cmd);
    advance();
    return 1;
  }
  const VkDeviceSize bytes = VkDeviceSize(settings_.width) * settings_.height * n * sizeof(glm::vec4);
  if (sampleSlots_.size() < bytes) {
    ctx_.waitIdle();  // the smaller buffer may be in flight
    sampleSlots_ = vk::Buffer(ctx_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    bindResources();
  }
  recordRegion(cmd, PixelRegion{0, 0, settings_.width, settings_.height}, n);
  sampleIndex_ += n;
  return n;
}

void PathTracer::recordRegion(VkCommandBuffer cmd, const PixelRegion& r, uint32_t samples) {
  // A material edit rebuilt the area lights' buffers (at a frame boundary, nothing in flight): point at them.
  if (gpuScene_.emitterVersion() != emitterVersion_) bindResources();
  if (sampleIndex_ == 0 && r.x == 0 && r.y == 0) updateFrameUniforms();
  // A restart: the inspector's slots still hold the previous accumulation's samples.
  if (inspection_ && sampleIndex_ == 0 && lastRecordedSample_ != 0) {
    vkCmdFillBuffer(cmd, inspectSamples_.handle(), 0, VK_WHOLE_SIZE, WB_INSPECT_NO_SAMPLE);
    vk::memoryBarrier(cmd);
  }
  // A restart counts the asserts' failures anew.
  if (instrumentation_.asserts && sampleIndex_ == 0 && r.x == 0 && r.y == 0) {
    vkCmdFillBuffer(cmd, assertHeader_.handle(), 0, sizeof(uint32_t), 0);
    vk::memoryBarrier(cmd);
  }
  // Lane isolation: every launch starts its pixel queue anew (raygen.rgen).
  if (isolatesLanes()) {
    vkCmdFillBuffer(cmd, counters_.handle(), offsetof(gpu::Counters, isolateNext), sizeof(uint32_t), 0);
    vk::memoryBarrier(cmd);
  }
  lastRecordedSample_ = sampleIndex_;
  gpu::PushConstants pc{};
  pc.sampleIndex = sampleIndex_;
  pc.maxBounces = settings_.maxBounces;
  pc.rrStart = settings_.rrStart;
  pc.rrMin = settings_.rrMin;
  pc.rrMax = settings_.rrMax;
  pc.rrExponent = settings_.rrExponent;
  pc.flags = (settings_.sampler == SamplerKind::Pcg ? WB_FLAG_SAMPLER_PCG : 0u) |
             (settings_.sampler == SamplerKind::Owen ? WB_FLAG_SAMPLER_OWEN : 0u) |
             (settings_.nee ? 0u : WB_FLAG_NO_NEE) | (settings_.mis ? 0u : WB_FLAG_NO_BRDF_MIS) |
             (settings_.russianRoulette ? 0u : WB_FLAG_NO_RR) |
             (settings_.aov || settings_.denoise ? WB_FLAG_AOV : 0u);
  pc.seed = settings_.seed;
  pc.debugView = settings_.debugView;
  pc.tileOffset = glm::uvec2(r.x, r.y);
  pc.imageSize = glm::uvec2(settings_.width, settings_.height);
  pc.splitSlots = splitSlots_;

  vk::GpuTimer::Scope timed(timer_.get(), cmd, "pathtracer", samples);  // GPU time per sample
  pass_->bind(cmd);
  pass_->push(cmd, pc);
  pass_->traceRays(cmd, r.width, r.height, samples);
  vk::memoryBarrier(cmd);
  if (split_) {  // the shadow launch accumulates the samples (or leaves them in the slots for the resolve)
    shadowPass_->bind(cmd);
    shadowPass_->push(cmd, pc);
    shadowPass_->traceRays(cmd, r.width, r.height, samples);
    vk::memoryBarrier(cmd);
  }
  if (samples > 1) {
    gpu::ResolveConstants rc{};
    rc.imageSize = pc.imageSize;
    rc.firstSample = sampleIndex_;
    rc.samples = samples;
    resolve_->bind(cmd);
    resolve_->push(cmd, rc);
    resolve_->dispatch(cmd, (r.width + 7) / 8, (r.height + 7) / 8);
    vk::memoryBarrier(cmd);
  }
}

void PathTracer::record(VkCommandBuffer cmd) {
  const uint32_t tw = settings_.tileWidth ? settings_.tileWidth : settings_.width;
  const uint32_t th = settings_.tileHeight ? settings_.tileHeight : settings_.height;
  for (uint32_t y = 0; y < settings_.height; y += th) {
    for (uint32_t x = 0; x < settings_.width; x += tw)
      recordRegion(cmd,
                   PixelRegion{x, y, std::min(tw, settings_.width - x), std::min(th, settings_.height - y)});
  }
}

std::vector<double> PathTracer::renderPixel(uint32_t x, uint32_t y, uint32_t samples) {
  if (x >= settings_.width || y >= settings_.height) throw std::invalid_argument("pixel outside the image");
  std::vector<double> seconds;
  sampleIndex_ = 0;
  for (uint32_t i = 0; i < samples; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
      if (sampleIndex_ == 0) updateFrameUniforms();
      recordRegion(cmd, PixelRegion{x, y, 1, 1});
    });
    advance();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return seconds;
}

double PathTracer::denoise() {
  if (!denoiser_) {
    denoiser_ = std::make_unique<Denoiser>(ctx_, library_);
    bindResources();
  }
  const auto t0 = std::chrono::steady_clock::now();
  ctx_.submitAndWait([&](VkCommandBuffer cmd) { denoiser_->record(cmd); });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

eval::ImageRGBA PathTracer::readImage() const {
  if (!settings_.denoise || !denoiser_) return readEstimate();
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    vk::GpuTimer::Scope timed(timer_.get(), cmd, "denoise");
    denoiser_->record(cmd);
  });
  timer_->collect();  // pass_ms' "denoise" (a round of its own)
  return readDenoised();
}

eval::ImageRGBA PathTracer::readDenoised() const {
  if (!denoiser_) throw std::logic_error("readDenoised: the denoiser has not run");
  eval::ImageRGBA img;
  img.width = settings_.width;
  img.height = settings_.height;
  img.pixels = denoiser_->readOutput();
  for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
  return img;
}

eval::ImageRGBA PathTracer::readEstimate() const {
  return Renderer::readImage();
}

std::vector<float> PathTracer::readAccumulation() const {
  return readFloatImage(accum_);
}

eval::CostSummary PathTracer::summarizeCost(const std::vector<float>& costAov) const {
  const auto estimate = ctx_.policy().costByMedian ? eval::CostEstimate::Median : eval::CostEstimate::Mean;
  eval::CostSummary s = eval::summarizeCost(readAccumulation(), readAov(Aov::Stats), costAov, settings_.width,
                                            settings_.height, clock_, estimate);
  s.lanesIsolated = isolatesLanes();
  return s;
}

std::vector<float> PathTracer::readAov(Aov aov) const {
  if (aov == Aov::Stats || aov == Aov::Cost) return readFloatImage(aovImage(aov));
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
