#include "render/environment.h"

namespace wb::render {

GpuEnvironment::GpuEnvironment(vk::Context& ctx, const EnvironmentData& data)
    : ctx_(ctx),
      width_(data.width),
      height_(data.height),
      totalWeight_(data.totalWeight),
      isMap_(data.isMap) {
  const size_t texels = size_t(width_) * height_;
  if (data.rgb.size() != texels * 3)
    throw std::runtime_error("environment: pixel data does not match its size");
  std::vector<float> rgba(texels * 4);
  for (size_t i = 0; i < texels; ++i) {
    rgba[4 * i + 0] = data.rgb[3 * i + 0];
    rgba[4 * i + 1] = data.rgb[3 * i + 1];
    rgba[4 * i + 2] = data.rgb[3 * i + 2];
    rgba[4 * i + 3] = 1.0f;
  }
  image_ = vk::Image(ctx, width_, height_, VK_FORMAT_R32G32B32A32_SFLOAT,
                     VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  image_.upload(rgba.data(), rgba.size() * sizeof(float), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  std::vector<gpu::EnvAliasEntry> alias = data.alias;
  if (alias.empty()) alias.push_back({1.0f, 0u, 1.0f, 0.0f});
  alias_ = vk::makeBuffer(ctx, alias, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  // Nearest filtering keeps the looked-up radiance exactly the piecewise-constant function the alias table
  // samples.
  VkSamplerCreateInfo ci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  ci.magFilter = VK_FILTER_NEAREST;
  ci.minFilter = VK_FILTER_NEAREST;
  ci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  ci.addressModeU = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  ci.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  ci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  WB_VK(vkCreateSampler(ctx.device(), &ci, nullptr, &sampler_));
}

GpuEnvironment::~GpuEnvironment() {
  if (sampler_) vkDestroySampler(ctx_.device(), sampler_, nullptr);
}

}  // namespace wb::render
