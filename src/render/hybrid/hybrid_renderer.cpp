#include "render/hybrid/hybrid_renderer.h"

#include <chrono>
#include <cmath>
#include <cstring>
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

const char* HybridRenderer::passName(Pass p) {
  switch (p) {
    case Pass::GBuffer:
      return "hybrid gbuffer (raster)";
    case Pass::ShadowAo:
      return "hybrid shadow+ao (ray tracing)";
    case Pass::Reflection:
      return "hybrid reflections (ray tracing)";
    default:
      return "hybrid composite (compute)";
  }
}

std::vector<shader::ShaderKey> HybridRenderer::stageKeys(Pass pass, const std::filesystem::path& shaderRoot) {
  const auto dir = (shaderRoot.empty() ? shaderDir() : shaderRoot) / "hybrid";
  switch (pass) {
    case Pass::GBuffer:
      return {{dir / "gbuffer.vert"}, {dir / "gbuffer.frag"}};
    case Pass::ShadowAo:
      return {{dir / "shadow_ao.rgen"}, {dir / "occlusion.rmiss"}, {dir / "alpha.rahit"}};
    case Pass::Reflection:
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
  {
    vk::DescriptorSets recorder(ctx_);
    writeDescriptors(recorder);
    provided_ = recorder.requested();
  }

  static const char* programNames[kPassCount] = {"hybrid-gbuffer", "hybrid-shadow-ao", "hybrid-reflections",
                                                 "hybrid-composite"};
  for (size_t i = 0; i < kPassCount; ++i) {
    const Pass pass = static_cast<Pass>(i);
    if (!hasPass(pass)) continue;
    programs_[i] = library_.registerProgram(programNames[i], stageKeys(pass, shaderRoot_));
    installPipeline(programs_[i], buildPipeline(programs_[i], library_.buildProgram(programs_[i])));
  }
}

HybridRenderer::~HybridRenderer() {
  ctx_.waitIdle();
  for (auto& s : sets_) s.reset();
  for (auto& p : pipelines_) p.reset();
  if (nearest_) vkDestroySampler(ctx_.device(), nearest_, nullptr);
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

void HybridRenderer::writeDescriptors(vk::DescriptorSets& s) {
  s.writeAccelerationStructure(0, WB_BIND_TLAS, gpuScene_.tlas());
  s.writeBuffer(0, WB_BIND_GEOMETRIES, gpuScene_.geometries().handle());
  s.writeBuffer(0, WB_BIND_MATERIALS, gpuScene_.materials().handle());
  s.writeSampledImages(0, WB_BIND_TEXTURES, gpuScene_.textureDescriptors());
  s.writeSampledImages(0, WB_BIND_ENV_MAP, {env_->descriptor()});
  s.writeBuffer(0, WB_BIND_HYBRID_FRAME, uniforms_.handle());
  auto sampled = [&](const vk::Image& img) {
    return std::vector<VkDescriptorImageInfo>{
        {nearest_, img.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
  };
  s.writeSampledImages(0, WB_BIND_GBUF_ALBEDO, sampled(albedo_));
  s.writeSampledImages(0, WB_BIND_GBUF_NORMAL, sampled(normal_));
  s.writeSampledImages(0, WB_BIND_GBUF_DEPTH, sampled(depth_));
  s.writeSampledImages(0, WB_BIND_GBUF_EMISSIVE, sampled(emissive_));
  s.writeStorageImage(0, WB_BIND_SHADOW_MASK, shadowMask_.view());
  s.writeStorageImage(0, WB_BIND_AO_MASK, aoMask_.view());
  s.writeStorageImage(0, WB_BIND_HYBRID_HISTORY, history_.view());
  s.writeStorageImage(0, WB_BIND_REFLECTION, reflection_.view());
  s.writeStorageImage(0, WB_BIND_HYBRID_OUTPUT, output_.view());
  s.writeBuffer(0, WB_BIND_HYBRID_INSPECT, inspect_.handle());
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

std::optional<HybridRenderer::Pass> HybridRenderer::passOf(shader::ShaderLibrary::ProgramId program) const {
  for (size_t i = 0; i < kPassCount; ++i)
    if (hasPass(Pass(i)) && programs_[i] == program) return Pass(i);
  return std::nullopt;
}

std::vector<RendererProgram> HybridRenderer::programs() const {
  std::vector<RendererProgram> out;
  for (size_t i = 0; i < kPassCount; ++i)
    if (hasPass(Pass(i))) out.push_back({programs_[i], passName(Pass(i))});
  return out;
}

std::unique_ptr<vk::BuiltPipeline> HybridRenderer::buildPipeline(
    shader::ShaderLibrary::ProgramId program, const shader::ShaderLibrary::ProgramBuild& build) const {
  const auto pass = passOf(program);
  if (!pass) throw std::invalid_argument("program " + std::to_string(program) + " is not a hybrid pass");
  vk::requireProvided(build, provided_, std::string("the ") + passName(*pass) + " pass");
  auto p = std::make_unique<vk::BuiltPipeline>();
  p->layout = std::make_unique<vk::PipelineLayout>(ctx_, build.layout);
  switch (*pass) {
    case Pass::GBuffer: {
      vk::GraphicsPipelineDesc desc;
      desc.colorFormats = {kAlbedoFormat, kNormalFormat, kEmissiveFormat};
      desc.depthFormat = kDepthFormat;
      desc.depthCompare = VK_COMPARE_OP_GREATER;  // reversed Z
      desc.cullMode = VK_CULL_MODE_NONE;
      desc.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
      p->graphics = std::make_unique<vk::GraphicsPipeline>(ctx_, build.stages, desc, p->layout->handle());
      break;
    }
    case Pass::ShadowAo: {
      // Miss 0 = shadow rays, miss 1 = AO rays (the same "nothing hit" shader); one hit group with only the
      // alpha any-hit (occlusion rays skip closest-hit).
      vk::RtBindingTable table;
      table.raygen("shadow_ao.rgen")
          .miss("occlusion.rmiss")
          .miss("occlusion.rmiss")
          .hitGroup({.anyHit = "alpha.rahit"});
      p->rayTracing =
          std::make_unique<vk::RayTracingPipeline>(ctx_, build.stages, table, p->layout->handle(), 1);
      break;
    }
    case Pass::Reflection: {
      // Miss 0 = reflected environment, miss 1 = occlusion (shadow rays of reflected hits).
      vk::RtBindingTable table;
      table.raygen("reflect.rgen")
          .miss("reflect.rmiss")
          .miss("occlusion.rmiss")
          .hitGroup({.closestHit = "reflect.rchit", .anyHit = "alpha.rahit"});
      p->rayTracing = std::make_unique<vk::RayTracingPipeline>(
          ctx_, build.stages, table, p->layout->handle(), 1,
          std::vector<vk::SpecializationConstant>{{0, hybrid_.reflectionDepth}});
      break;
    }
    case Pass::Composite: {
      const vk::ShaderModule module(ctx_.device(), *build.stages.at(0));
      VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
      ci.stage = module.stageInfo();
      ci.layout = p->layout->handle();
      VkPipeline compute = VK_NULL_HANDLE;
      WB_VK(vkCreateComputePipelines(ctx_.device(), ctx_.pipelineCache(), 1, &ci, nullptr, &compute));
      p->other = vk::OwnedPipeline(ctx_.device(), compute);
      break;
    }
  }
  return p;
}

std::shared_ptr<vk::BuiltPipeline> HybridRenderer::pipeline(shader::ShaderLibrary::ProgramId program) const {
  const auto pass = passOf(program);
  return pass ? pipelines_[size_t(*pass)] : nullptr;
}

std::shared_ptr<vk::BuiltPipeline> HybridRenderer::exchangePipeline(
    shader::ShaderLibrary::ProgramId program, std::shared_ptr<vk::BuiltPipeline> pipeline) {
  const auto pass = passOf(program);
  if (!pass) return nullptr;
  ctx_.waitIdle();  // the old pipeline and descriptor sets may still be in flight
  const size_t i = size_t(*pass);
  sets_[i].reset();
  std::swap(pipelines_[i], pipeline);
  sets_[i] = std::make_unique<vk::DescriptorSets>(ctx_, *pipelines_[i]->layout);
  if (!sets_[i]->sets().empty()) writeDescriptors(*sets_[i]);
  builds_[i]++;
  frameIndex_ = 0;
  return pipeline;
}

uint32_t HybridRenderer::pipelineInstalls() const {
  uint32_t n = 0;
  for (uint32_t b : builds_) n += b;
  return n;
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

VkPipeline HybridRenderer::pipelineHandle(Pass p) const {
  const auto& pl = pipelines_[size_t(p)];
  return pl ? pl->handle() : VK_NULL_HANDLE;
}

VkPipelineBindPoint HybridRenderer::bindPoint(Pass pass) const {
  switch (pass) {
    case Pass::GBuffer:
      return VK_PIPELINE_BIND_POINT_GRAPHICS;
    case Pass::Composite:
      return VK_PIPELINE_BIND_POINT_COMPUTE;
    default:
      return VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR;
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
    for (size_t i = 0; i < kPassCount; ++i) {
      if (sets_[i] && !sets_[i]->sets().empty()) writeDescriptors(*sets_[i]);
    }
  }
  frameIndex_ = 0;
}

void HybridRenderer::setHybridSettings(const HybridSettings& hybrid) {
  const bool depthChanged = hybrid.reflectionDepth != hybrid_.reflectionDepth;
  hybrid_ = hybrid;
  if (depthChanged && hasPass(Pass::Reflection)) {
    const auto id = programs_[size_t(Pass::Reflection)];
    installPipeline(id, buildPipeline(id, library_.buildProgram(id)));
  }
  frameIndex_ = 0;
}

void HybridRenderer::setEnvironment(const GpuEnvironment& env) {
  ctx_.waitIdle();
  env_ = &env;
  for (size_t i = 0; i < kPassCount; ++i) {
    if (sets_[i] && !sets_[i]->sets().empty()) writeDescriptors(*sets_[i]);
  }
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
  auto bind = [&](Pass pass) {
    const auto& pl = *pipelines_[size_t(pass)];
    vkCmdBindPipeline(cmd, bindPoint(pass), pl.handle());
    const auto& sets = sets_[size_t(pass)]->sets();
    if (!sets.empty()) {
      vkCmdBindDescriptorSets(cmd, bindPoint(pass), pl.layout->handle(), 0,
                              static_cast<uint32_t>(sets.size()), sets.data(), 0, nullptr);
    }
    return pl.layout.get();
  };

  // 1. G-buffer (dynamic rendering). The previous contents are discarded.
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
    const vk::PipelineLayout* layout = bind(Pass::GBuffer);
    vk::setViewportAndScissor(cmd, w, h);
    for (const auto& d : draws_) {
      gpu::HybridDrawConstants pc{};
      pc.model = d.model;
      pc.geometryIndex = d.geometry;
      for (const auto& range : layout->desc().pushConstants) {
        vkCmdPushConstants(cmd, layout->handle(), range.stageFlags, range.offset, range.size,
                           reinterpret_cast<const char*>(&pc) + range.offset);
      }
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
  bind(Pass::ShadowAo);
  pipelines_[size_t(Pass::ShadowAo)]->rayTracing->sbt().trace(ctx_, cmd, w, h);
  vk::memoryBarrier(cmd);
  if (hasPass(Pass::Reflection)) {
    bind(Pass::Reflection);
    pipelines_[size_t(Pass::Reflection)]->rayTracing->sbt().trace(ctx_, cmd, w, h);
    vk::memoryBarrier(cmd);
  }

  // 4. Composite.
  bind(Pass::Composite);
  vkCmdDispatch(cmd, (w + 7) / 8, (h + 7) / 8, 1);
  vk::memoryBarrier(cmd);
}

eval::ImageRGBA HybridRenderer::readImage() const {
  eval::ImageRGBA img;
  img.width = settings_.width;
  img.height = settings_.height;
  img.pixels = readOutput();
  for (size_t i = 3; i < img.pixels.size(); i += 4) img.pixels[i] = 1.0f;
  return img;
}

std::vector<float> HybridRenderer::readOutput() const {
  auto bytes = output_.download(VK_IMAGE_LAYOUT_GENERAL);
  std::vector<float> out(bytes.size() / sizeof(float));
  std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
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
