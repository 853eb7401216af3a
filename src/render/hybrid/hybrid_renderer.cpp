#include "render/hybrid/hybrid_renderer.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>
#include <utility>

#include "common/half.h"
#include "common/paths.h"
#include "vk/shader_module.h"

namespace wb::render {
namespace {

constexpr VkFormat kAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;
constexpr VkFormat kNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kEmissiveFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

// Reversed-Z infinite perspective (depth = znear / distance), y flipped like the path tracer's projection so
// both put image row 0 at the top and agree on every pixel's ray.
glm::mat4 reversedInfinitePerspective(float yfov, float aspect, float znear) {
  const float f = 1.0f / std::tan(yfov * 0.5f);
  glm::mat4 p(0.0f);
  p[0][0] = f / aspect;
  p[1][1] = -f;
  p[2][3] = -1.0f;
  p[3][2] = znear;
  return p;
}

}  // namespace

const char* HybridRenderer::passName(HybridPass p) {
  switch (p) {
    case HybridPass::GBuffer:
      return "hybrid gbuffer (raster)";
    case HybridPass::ShadowAo:
      return "hybrid shadow+ao (ray tracing)";
    case HybridPass::Reflection:
      return "hybrid reflections (ray tracing)";
    default:
      return "hybrid composite (compute)";
  }
}

const char* HybridRenderer::passKey(HybridPass p) {
  switch (p) {
    case HybridPass::GBuffer:
      return "gbuffer";
    case HybridPass::ShadowAo:
      return "shadow_ao";
    case HybridPass::Reflection:
      return "reflections";
    default:
      return "composite";
  }
}

std::vector<shader::ShaderKey> HybridRenderer::stageKeys(HybridPass pass,
                                                         const std::filesystem::path& shaderRoot) {
  const auto dir = (shaderRoot.empty() ? shaderDir() : shaderRoot) / "hybrid";
  switch (pass) {
    case HybridPass::GBuffer:
      return {{dir / "gbuffer.vert"}, {dir / "gbuffer.frag"}};
    case HybridPass::ShadowAo:
      return {{dir / "shadow_ao.rgen"}, {dir / "occlusion.rmiss"}, {dir / "alpha.rahit"}};
    case HybridPass::Reflection:
      return {{dir / "reflect.rgen"},
              {dir / "reflect.rmiss"},
              {dir / "occlusion.rmiss"},
              {dir / "reflect.rchit"},
              {dir / "alpha.rahit"}};
    default:
      return {{dir / "composite.comp"}};
  }
}

HybridRenderer::HybridRenderer(const RendererResources& r, const RenderSettings& settings, RenderMode mode,
                               const HybridSettings& hybrid, const std::filesystem::path& shaderRoot)
    : ctx_(r.ctx),
      library_(r.library),
      gpuScene_(r.gpuScene),
      env_(&r.environment),
      settings_(settings),
      mode_(mode == RenderMode::PathTrace ? RenderMode::Hybrid : mode),
      hybrid_(hybrid),
      shaderRoot_(shaderRoot.empty() ? shaderDir() : shaderRoot) {
  // One draw per (instance, primitive); GpuScene made one GeometryInfo per primitive, meshes in order.
  const scene::Scene& scene = r.scene;
  std::vector<uint32_t> firstGeometry;
  uint32_t geometryCount = 0;
  for (const auto& mesh : scene.meshes) {
    firstGeometry.push_back(geometryCount);
    geometryCount += static_cast<uint32_t>(mesh.primitives.size());
  }
  for (const auto& inst : scene.instances) {
    if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
    const auto& mesh = scene.meshes[inst.mesh];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const uint32_t corners = static_cast<uint32_t>(mesh.primitives[p].indices.size() / 3 * 3);
      if (corners == 0) continue;
      draws_.push_back({inst.transform, firstGeometry[inst.mesh] + static_cast<uint32_t>(p), corners});
    }
  }
  if (!scene.lights.empty()) {
    sun_ = scene.lights.front();
    hasSun_ = true;
  }
  cameraDistance_ = std::max(glm::length(scene.camera.eye - scene.camera.target), 1e-3f);
  camera_ = cameraFromScene(scene.camera);

  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = VK_FILTER_NEAREST;
  sci.minFilter = VK_FILTER_NEAREST;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  WB_VK(vkCreateSampler(ctx_.device(), &sci, nullptr, &nearest_));
  uniforms_ = vk::Buffer(ctx_, sizeof(gpu::HybridUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
  inspect_ = vk::Buffer(ctx_, sizeof(gpu::HybridInspectRecord), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
  setInspectPixel(std::nullopt);
  createImages();

  // How each pass's program becomes a pipeline.
  PipelineRecipe recipes[kPassCount];
  {
    GraphicsRecipe g;
    g.desc.colorFormats = {kAlbedoFormat, kNormalFormat, kEmissiveFormat};
    g.desc.depthFormat = kDepthFormat;
    g.desc.depthCompare = VK_COMPARE_OP_GREATER;  // reversed Z
    g.desc.cullMode = VK_CULL_MODE_NONE;
    g.desc.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    recipes[size_t(HybridPass::GBuffer)] = g;
    // Miss 0 = shadow rays, miss 1 = AO rays (the same "nothing hit" shader); one hit group with only the
    // alpha any-hit (occlusion rays skip closest-hit).
    RayTracingRecipe shadow;
    shadow.table.raygen("shadow_ao.rgen")
        .miss("occlusion.rmiss")
        .miss("occlusion.rmiss")
        .hitGroup({.anyHit = "alpha.rahit"});
    recipes[size_t(HybridPass::ShadowAo)] = shadow;
    recipes[size_t(HybridPass::Reflection)] = reflectionRecipe();
    recipes[size_t(HybridPass::Composite)] = ComputeRecipe{};
  }
  static const char* programNames[kPassCount] = {"hybrid-gbuffer", "hybrid-shadow-ao", "hybrid-reflections",
                                                 "hybrid-composite"};
  timer_ = std::make_unique<vk::GpuTimer>(ctx_);
  for (size_t i = 0; i < kPassCount; ++i) {
    const HybridPass id = static_cast<HybridPass>(i);
    if (!hasPass(id)) continue;
    passes_[i] = std::make_unique<Pass>(ctx_, library_, passName(id), recipes[i]);
    passes_[i]->setOnInstall([this] { frameIndex_ = 0; });
    if (id == HybridPass::GBuffer) passes_[i]->setPushConstantBytes(sizeof(gpu::HybridDrawConstants));
    passes_[i]->useProgram(programNames[i], stageKeys(id, shaderRoot_));
  }
  bindResources();
  for (auto& p : passes_)
    if (p) p->rebuild();
}

HybridRenderer::~HybridRenderer() {
  ctx_.waitIdle();
  for (auto& p : passes_) p.reset();
  if (nearest_) vkDestroySampler(ctx_.device(), nearest_, nullptr);
}

RayTracingRecipe HybridRenderer::reflectionRecipe() const {
  // Miss 0 = reflected environment, miss 1 = occlusion (shadow rays of reflected hits).
  RayTracingRecipe r;
  r.table.raygen("reflect.rgen")
      .miss("reflect.rmiss")
      .miss("occlusion.rmiss")
      .hitGroup({.closestHit = "reflect.rchit", .anyHit = "alpha.rahit"});
  r.constants = {{0, hybrid_.reflectionDepth}};
  return r;
}

void HybridRenderer::createImages() {
  const uint32_t w = settings_.width, h = settings_.height;
  const VkImageUsageFlags attachment =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  const VkImageUsageFlags storage =
      VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  albedo_ = vk::Image(ctx_, w, h, kAlbedoFormat, attachment);
  normal_ = vk::Image(ctx_, w, h, kNormalFormat, attachment);
  emissive_ = vk::Image(ctx_, w, h, kEmissiveFormat, attachment);
  depth_ = vk::Image(ctx_, w, h, kDepthFormat,
                     VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT);
  shadowMask_ = vk::Image(ctx_, w, h, VK_FORMAT_R8_UNORM, storage);
  aoMask_ = vk::Image(ctx_, w, h, VK_FORMAT_R8_UNORM, storage);
  // 32-bit floats: the running average over many frames stays unbiased whatever the driver's rounding to 16
  // bits.
  history_ = vk::Image(ctx_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, storage);
  reflection_ = vk::Image(ctx_, w, h, VK_FORMAT_R16G16B16A16_SFLOAT, storage);
  output_ = vk::Image(ctx_, w, h, VK_FORMAT_R32G32B32A32_SFLOAT, storage | VK_IMAGE_USAGE_SAMPLED_BIT);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* img : {&albedo_, &normal_, &emissive_}) {
      vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    }
    vk::transition(cmd, depth_.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   VK_IMAGE_ASPECT_DEPTH_BIT);
    for (const vk::Image* img : {&shadowMask_, &aoMask_, &history_, &reflection_, &output_}) {
      vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      VkClearColorValue zero{};
      VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, img->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    }
    vk::memoryBarrier(cmd);
  });
  frameIndex_ = 0;
}

void HybridRenderer::bindResources() {
  auto sampled = [&](const vk::Image& img) {
    return std::vector<VkDescriptorImageInfo>{
        {nearest_, img.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  };
  for (auto& pass : passes_) {
    if (!pass) continue;
    Pass& p = *pass;
    bindSceneResources(p, gpuScene_, *env_);
    p.setBuffer("HybridFrameBlock", uniforms_);
    p.setSampledImages("gbufAlbedo", sampled(albedo_));
    p.setSampledImages("gbufNormal", sampled(normal_));
    p.setSampledImages("gbufDepth", sampled(depth_));
    p.setSampledImages("gbufEmissive", sampled(emissive_));
    p.setStorageImage("shadowMask", shadowMask_.view());
    p.setStorageImage("aoMask", aoMask_.view());
    p.setStorageImage("history", history_.view());
    p.setStorageImage("reflectionImage", reflection_.view());
    p.setStorageImage("outputImage", output_.view());
    p.setBuffer("HybridInspectBlock", inspect_);
  }
}

void HybridRenderer::setInspectPixel(std::optional<glm::uvec2> pixel) {
  ctx_.waitIdle();  // a frame in flight may be writing the record
  inspectPixel_ = pixel;
  gpu::HybridInspectRecord empty{};
  empty.frameIndex = WB_HYBRID_NO_INSPECT;
  std::memcpy(inspect_.mapped(), &empty, sizeof(empty));
}

gpu::HybridInspectRecord HybridRenderer::readInspection() const {
  gpu::HybridInspectRecord r;
  std::memcpy(&r, inspect_.mapped(), sizeof(r));
  return r;
}

std::vector<Pass*> HybridRenderer::passes() const {
  std::vector<Pass*> out;
  for (const auto& p : passes_)
    if (p) out.push_back(p.get());
  return out;
}

std::unique_ptr<Renderer> HybridRenderer::makeLike(const RendererResources& resources,
                                                   const RenderSettings& settings) const {
  return std::make_unique<HybridRenderer>(resources, settings, mode_, hybrid_, shaderRoot_);
}

void HybridRenderer::matchCompiledParameters(const Renderer& other) {
  // The reflection depth is a specialisation constant: a new one rebuilds the reflection pipeline.
  const auto& o = dynamic_cast<const HybridRenderer&>(other).hybrid_;
  if (o.reflectionDepth != hybrid_.reflectionDepth) {
    HybridSettings h = hybrid_;
    h.reflectionDepth = o.reflectionDepth;
    setHybridSettings(h);
  }
}

void HybridRenderer::setCamera(const CameraState& camera) {
  camera_ = camera;
  frameIndex_ = 0;
}

void HybridRenderer::setSettings(const RenderSettings& settings) {
  const bool resized = settings.width != settings_.width || settings.height != settings_.height;
  settings_ = settings;
  if (resized) {
    ctx_.waitIdle();
    createImages();
    bindResources();
  }
  frameIndex_ = 0;
}

void HybridRenderer::setHybridSettings(const HybridSettings& hybrid) {
  const bool depthChanged = hybrid.reflectionDepth != hybrid_.reflectionDepth;
  hybrid_ = hybrid;
  if (depthChanged && hasPass(HybridPass::Reflection)) {
    pass(HybridPass::Reflection).setRecipe(reflectionRecipe());
    pass(HybridPass::Reflection).rebuild();
  }
  frameIndex_ = 0;
}

void HybridRenderer::setEnvironment(const GpuEnvironment& env) {
  ctx_.waitIdle();
  env_ = &env;
  bindResources();
  frameIndex_ = 0;
}

void HybridRenderer::setLights(const std::vector<gpu::DirectionalLight>& lights) {
  hasSun_ = !lights.empty();
  if (hasSun_) sun_ = lights.front();
  frameIndex_ = 0;
}

float HybridRenderer::aoRadius() const {
  return hybrid_.aoRadius > 0.0f ? hybrid_.aoRadius : 0.15f * cameraDistance_;
}

float HybridRenderer::sunCosAngle() const {
  return scene::sunCosAngularRadius(hasSun_ ? sun_.cosAngularRadius : 1.0f, settings_.sunAngleDeg);
}

void HybridRenderer::updateUniforms() {
  gpu::HybridUniforms u{};
  const float aspect = float(settings_.width) / float(settings_.height);
  u.viewProj = reversedInfinitePerspective(camera_.yfov, aspect, camera_.znear) * camera_.view;
  u.viewProjInverse = glm::inverse(u.viewProj);
  u.cameraPosition = glm::vec3(glm::inverse(camera_.view)[3]);
  u.frameIndex = frameIndex_;
  u.sunDirection = hasSun_ ? glm::normalize(sun_.direction) : glm::vec3(0, -1, 0);
  u.sunCosAngle = sunCosAngle();
  u.sunRadiance = hasSun_ ? sun_.radiance : glm::vec3(0.0f);
  u.hasSun = hasSun_ ? 1u : 0u;
  u.ambient = env_->isMap() ? glm::vec3(0.0f) : settings_.envColor * settings_.envIntensity;
  u.aoRadius = aoRadius();
  u.aoRays = hybrid_.aoRays;
  u.flags = (mode_ == RenderMode::Reflections ? WB_HYBRID_FLAG_REFLECTIONS : 0u) |
            (hybrid_.aoRays > 0 ? WB_HYBRID_FLAG_AO : 0u) | (hybrid_.temporal ? WB_HYBRID_FLAG_TEMPORAL : 0u);
  u.width = settings_.width;
  u.height = settings_.height;
  u.reflectionMaxRoughness = hybrid_.reflectionMaxRoughness;
  u.reflectionMinMetallic = hybrid_.reflectionMinMetallic;
  u.envIntensity = settings_.envIntensity;
  u.envRotation = glm::radians(settings_.envRotationDeg);
  u.envMapPresent = env_->isMap() ? 1u : 0u;
  u.seed = settings_.seed * 0x9E3779B9u;
  u.inspectX = inspectPixel_ ? inspectPixel_->x : WB_HYBRID_NO_INSPECT;
  u.inspectY = inspectPixel_ ? inspectPixel_->y : WB_HYBRID_NO_INSPECT;
  std::memcpy(uniforms_.mapped(), &u, sizeof(u));
}

void HybridRenderer::record(VkCommandBuffer cmd) {
  updateUniforms();
  const uint32_t w = settings_.width, h = settings_.height;

  // 1. G-buffer (dynamic rendering). The previous contents are discarded.
  std::optional<vk::GpuTimer::Scope> timed;  // each pass's GPU time
  timed.emplace(timer_.get(), cmd, passKey(HybridPass::GBuffer));
  for (const vk::Image* img : {&albedo_, &normal_, &emissive_}) {
    vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  }
  vk::transition(cmd, depth_.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_ASPECT_DEPTH_BIT);
  VkRenderingAttachmentInfo colors[3];
  const vk::Image* targets[3] = {&albedo_, &normal_, &emissive_};
  for (int i = 0; i < 3; ++i) {
    colors[i] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    colors[i].imageView = targets[i]->view();
    colors[i].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    colors[i].clearValue.color = VkClearColorValue{};
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = depth_.view();
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {0.0f, 0};  // reversed Z: 0 = infinitely far
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, {w, h}};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 3;
  ri.pColorAttachments = colors;
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  {
    const Pass& gbuffer = pass(HybridPass::GBuffer);
    gbuffer.bind(cmd);
    vk::setViewportAndScissor(cmd, w, h);
    for (const auto& d : draws_) {
      gpu::HybridDrawConstants pc{};
      pc.model = d.model;
      pc.geometryIndex = d.geometry;
      gbuffer.push(cmd, pc);
      vkCmdDraw(cmd, d.vertexCount, 1, 0, 0);
    }
  }
  vkCmdEndRendering(cmd);
  for (const vk::Image* img : {&albedo_, &normal_, &emissive_}) {
    vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  }
  vk::transition(cmd, depth_.handle(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_ASPECT_DEPTH_BIT);

  // 2. Shadows + AO, 3. reflections (ray tracing pipelines, launched over the image).
  for (HybridPass id : {HybridPass::ShadowAo, HybridPass::Reflection}) {
    if (!hasPass(id)) continue;
    timed.reset();
    timed.emplace(timer_.get(), cmd, passKey(id));
    pass(id).bind(cmd);
    pass(id).traceRays(cmd, w, h);
    vk::memoryBarrier(cmd);
  }

  // 4. Composite.
  timed.reset();
  timed.emplace(timer_.get(), cmd, passKey(HybridPass::Composite));
  pass(HybridPass::Composite).bind(cmd);
  pass(HybridPass::Composite).dispatch(cmd, (w + 7) / 8, (h + 7) / 8);
  vk::memoryBarrier(cmd);
}

std::vector<float> HybridRenderer::readOutput() const {
  return readFloatImage(output_);
}

std::vector<uint8_t> HybridRenderer::readShadowMask() const {
  return shadowMask_.download(VK_IMAGE_LAYOUT_GENERAL);
}

std::vector<uint8_t> HybridRenderer::readAoMask() const {
  return aoMask_.download(VK_IMAGE_LAYOUT_GENERAL);
}

std::vector<float> HybridRenderer::readReflection() const {
  return halvesToFloats(reflection_.download(VK_IMAGE_LAYOUT_GENERAL));
}

}  // namespace wb::render
