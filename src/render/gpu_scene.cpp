#include "render/gpu_scene.h"

#include "render/environment.h"
#include "render/pass.h"

#include "sampling/environment.h"
#include "scene/emitters.h"
#include "scene/reflectors.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace wb::render {
namespace {

VkFilter toFilter(int gl) {
  return gl == 9728 || gl == 9984 || gl == 9986 ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
}

VkSamplerAddressMode toAddress(int gl) {
  switch (gl) {
    case 33071:
      return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case 33648:
      return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default:
      return VK_SAMPLER_ADDRESS_MODE_REPEAT;
  }
}

}  // namespace

GpuScene::GpuScene(vk::Context& ctx, const scene::Scene& scene) : ctx_(ctx), source_(scene) {
  if (scene.instances.empty() || scene.triangleCount() == 0) {
    throw std::runtime_error("scene '" + scene.sourcePath.string() + "' has no triangles to render");
  }
  const VkBufferUsageFlags geometryUsage =
      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  std::vector<gpu::GeometryInfo> geometryInfos;
  std::vector<std::vector<vk::BlasGeometry>> blasMeshes;
  std::vector<uint32_t> firstGeometry;
  for (const auto& mesh : scene.meshes) {
    firstGeometry.push_back(static_cast<uint32_t>(geometryInfos.size()));
    std::vector<vk::BlasGeometry> blas;
    for (const auto& prim : mesh.primitives) {
      vertexBuffers_.push_back(vk::makeBuffer(ctx, prim.vertices, geometryUsage));
      indexBuffers_.push_back(vk::makeBuffer(ctx, prim.indices, geometryUsage));
      const auto& vb = vertexBuffers_.back();
      const auto& ib = indexBuffers_.back();
      gpu::GeometryInfo gi{};
      gi.vertexAddressLo = static_cast<uint32_t>(vb.address());
      gi.vertexAddressHi = static_cast<uint32_t>(vb.address() >> 32);
      gi.indexAddressLo = static_cast<uint32_t>(ib.address());
      gi.indexAddressHi = static_cast<uint32_t>(ib.address() >> 32);
      gi.materialIndex = static_cast<uint32_t>(std::max(prim.material, 0));
      gi.vertexCount = static_cast<uint32_t>(prim.vertices.size());
      gi.triangleCount = static_cast<uint32_t>(prim.indices.size() / 3);
      geometryInfos.push_back(gi);
      const auto& mat = scene.materials.at(gi.materialIndex);
      const bool opaque = mat.alphaMode == WB_ALPHA_OPAQUE;
      anyNonOpaque_ = anyNonOpaque_ || !opaque;
      blas.push_back(
          {vb.address(), sizeof(gpu::Vertex), gi.vertexCount, ib.address(), gi.triangleCount, opaque});
    }
    blasMeshes.push_back(std::move(blas));
  }
  geometries_ = vk::makeBuffer(ctx, geometryInfos, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  materials_ = vk::makeBuffer(ctx, scene.materials, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  lightCount_ = static_cast<uint32_t>(scene.lights.size());

  buildEmitters(scene.materials);

  std::vector<vk::TlasInstance> instances;
  for (const auto& inst : scene.instances) {
    instances.push_back(
        {static_cast<uint32_t>(inst.mesh), inst.transform, firstGeometry.at(inst.mesh), 0xFF});
  }
  accel_ = std::make_unique<vk::AccelerationStructures>(ctx, blasMeshes, instances);

  // Textures: sRGB for colour data, UNORM for normals and metallic-roughness; one image per texture (an image
  // used both ways is uploaded twice, which is rare).
  const uint8_t white[4] = {255, 255, 255, 255};
  auto addSampler = [&](const scene::Sampler& s) {
    VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    ci.magFilter = toFilter(s.magFilter);
    ci.minFilter = toFilter(s.minFilter);
    ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    ci.addressModeU = toAddress(s.wrapS);
    ci.addressModeV = toAddress(s.wrapT);
    ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
    ci.maxLod = 0.0f;
    VkSampler sampler;
    WB_VK(vkCreateSampler(ctx.device(), &ci, nullptr, &sampler));
    samplers_.push_back(sampler);
    return sampler;
  };
  for (size_t t = 0; t < scene.textures.size(); ++t) {
    const auto& tex = scene.textures[t];
    const bool srgb = t < scene.textureIsSrgb.size() && scene.textureIsSrgb[t];
    const scene::Image* img = tex.image >= 0 ? &scene.images.at(tex.image) : nullptr;
    const bool usable = img && img->width > 0 && img->height > 0;
    uint32_t w = usable ? img->width : 1, h = usable ? img->height : 1;
    images_.emplace_back(ctx, w, h, srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    images_.back().upload(usable ? img->rgba8.data() : white, VkDeviceSize(w) * h * 4,
                          VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    VkSampler sampler = addSampler(tex.sampler >= 0 ? scene.samplers.at(tex.sampler) : scene::Sampler{});
    textureInfos_.push_back({sampler, images_.back().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  }
  if (textureInfos_.empty()) {
    // Descriptor arrays may not be empty to bind; a single white texture stands in.
    images_.emplace_back(ctx, 1, 1, VK_FORMAT_R8G8B8A8_UNORM,
                         VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    images_.back().upload(white, 4, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    textureInfos_.push_back(
        {addSampler(scene::Sampler{}), images_.back().view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL});
  }
}

GpuScene::~GpuScene() {
  accel_.reset();
  for (auto s : samplers_) vkDestroySampler(ctx_.device(), s, nullptr);
}

void GpuScene::buildEmitters(const std::vector<gpu::Material>& materials) {
  const auto emitters = scene::emissiveTriangles(source_, materials);
  std::vector<gpu::EnvAliasEntry> alias;
  emitterTotalPower_ = 0.0f;
  if (!emitters.empty()) {
    const auto weights = scene::emitterWeights(materials, emitters);
    for (double w : weights) emitterTotalPower_ += float(w);
    alias = buildAliasTable(weights);
  }
  emitterCount_ = static_cast<uint32_t>(emitters.size());
  emitters_ = vk::makeBuffer(ctx_, emitters, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  emitterAlias_ = vk::makeBuffer(ctx_, alias, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const auto reflectors = scene::glossyReflectors(source_, materials);
  reflectorCount_ = static_cast<uint32_t>(reflectors.size());
  reflectors_ = vk::makeBuffer(ctx_, reflectors, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  ++emitterVersion_;
}

void GpuScene::updateMaterials(const std::vector<gpu::Material>& materials) {
  if (materials.size() != source_.materials.size()) {
    throw std::invalid_argument("updateMaterials: " + std::to_string(materials.size()) +
                                " materials, the scene has " + std::to_string(source_.materials.size()));
  }
  ctx_.waitIdle();  // the emitter buffers may be in use
  materials_.upload(materials.data(), materials.size() * sizeof(gpu::Material));
  buildEmitters(materials);
}

uint64_t GpuScene::deviceBytes() const {
  uint64_t total = accel_->memoryBytes() + geometries_.size() + materials_.size();
  for (const auto& b : vertexBuffers_) total += b.size();
  for (const auto& b : indexBuffers_) total += b.size();
  for (const auto& i : images_) total += VkDeviceSize(i.width()) * i.height() * 4;
  return total;
}

void bindSceneResources(Pass& pass, const GpuScene& scene, const GpuEnvironment& env) {
  pass.setAccelerationStructure("tlas", scene.tlas());
  pass.setBuffer("GeometryBlock", scene.geometries());
  pass.setBuffer("MaterialBlock", scene.materials());
  pass.setSampledImages("textures", scene.textureDescriptors());
  pass.setBuffer("EmitterBlock", scene.emitters());
  pass.setBuffer("EmitterAliasBlock", scene.emitterAlias());
  pass.setBuffer("ReflectorBlock", scene.reflectors());
  pass.setSampledImages("envMap", {env.descriptor()});
  pass.setBuffer("EnvAliasBlock", env.aliasTable());
}

}  // namespace wb::render
