#include "render/denoiser.h"

#include <algorithm>
#include <cstdlib>

#include "common/paths.h"

namespace wb::render {
namespace {

constexpr uint32_t kGroupSize = 8;  // local_size of shaders/denoise/*.comp
const char* const kPassNames[] = {"denoise prepare (compute)", "denoise variance (compute)",
                                  "denoise a-trous (compute)", "denoise final (compute)"};
const char* const kProgramNames[] = {"denoise-prepare", "denoise-variance", "denoise-atrous", "denoise-final"};
const char* const kFiles[] = {"prepare.comp", "variance.comp", "atrous.comp", "final.comp"};

}  // namespace

std::vector<shader::ShaderKey> Denoiser::stageKeys() {
  std::vector<shader::ShaderKey> keys;
  for (const char* f : kFiles) keys.push_back({shaderDir() / "denoise" / f});
  return keys;
}

Denoiser::Denoiser(vk::Context& ctx, shader::ShaderLibrary& library) : ctx_(ctx) {
  const auto keys = stageKeys();
  for (size_t i = 0; i < kPassCount; ++i) {
    passes_[i] = std::make_unique<Pass>(ctx_, library, kPassNames[i], ComputeRecipe{});
    passes_[i]->setPushConstantBytes(sizeof(gpu::DenoisePush));
    passes_[i]->useProgram(kProgramNames[i], {keys[i]});
  }
  resize(1, 1);
  for (auto& p : passes_) p->rebuild();
  // TUNING (not to commit)
  if (const char* e = std::getenv("WB_DN_SIGMA_L")) options_.sigmaLuminance = std::strtof(e, nullptr);
  if (const char* e = std::getenv("WB_DN_TAU")) options_.handoverTau = std::strtof(e, nullptr);
  if (const char* e = std::getenv("WB_DN_ITER")) options_.iterations = std::strtoul(e, nullptr, 10);
  if (const char* e = std::getenv("WB_DN_SIGMA_Z")) options_.sigmaDepth = std::strtof(e, nullptr);
}

Denoiser::~Denoiser() {
  ctx_.waitIdle();
  for (auto& p : passes_) p.reset();
}

void Denoiser::resize(uint32_t width, uint32_t height) {
  width = std::max(width, 1u);
  height = std::max(height, 1u);
  if (width == width_ && height == height_) return;
  ctx_.waitIdle();
  width_ = width;
  height_ = height;
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  guide_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  ping_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  pong_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  variance_ = vk::Image(ctx_, width, height, VK_FORMAT_R32_SFLOAT, usage);
  output_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    for (const vk::Image* img : {&guide_, &ping_, &pong_, &variance_, &output_}) {
      vk::transition(cmd, img->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
      VkClearColorValue zero{};
      VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
      vkCmdClearColorImage(cmd, img->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    }
  });
  bind();
}

void Denoiser::setInputs(const DenoiseInputs& inputs) {
  inputs_ = inputs;
  bind();
}

void Denoiser::bind() {
  for (auto& p : passes_) {
    p->setStorageImage("radianceImage", inputs_.radiance);
    p->setStorageImage("albedoImage", inputs_.albedo);
    p->setStorageImage("normalImage", inputs_.normal);
    p->setStorageImage("statsImage", inputs_.stats);
    p->setStorageImage("guideImage", guide_.view());
    p->setStorageImage("pingImage", ping_.view());
    p->setStorageImage("pongImage", pong_.view());
    p->setStorageImage("varianceImage", variance_.view());
    p->setStorageImage("outputImage", output_.view());
  }
}

std::vector<Pass*> Denoiser::passes() const {
  std::vector<Pass*> out;
  for (const auto& p : passes_) out.push_back(p.get());
  return out;
}

void Denoiser::dispatch(VkCommandBuffer cmd, const Pass& pass, const gpu::DenoisePush& push,
                        uint32_t rows) const {
  pass.bind(cmd);
  pass.push(cmd, push);
  pass.dispatch(cmd, (width_ + kGroupSize - 1) / kGroupSize, (rows + kGroupSize - 1) / kGroupSize);
  vk::memoryBarrier(cmd);
}

void Denoiser::record(VkCommandBuffer cmd, uint32_t rows) const {
  gpu::DenoisePush push{};
  push.imageSize = glm::uvec2(width_, height_);
  push.rows = std::min(rows, height_);
  push.sigmaLuminance = options_.sigmaLuminance;
  push.sigmaNormal = options_.sigmaNormal;
  push.sigmaDepth = options_.sigmaDepth;
  push.handoverTau = options_.handoverTau;
  vk::memoryBarrier(cmd);  // the path tracer's writes before the first read
  dispatch(cmd, *passes_[kPrepare], push, push.rows);
  dispatch(cmd, *passes_[kVariance], push, push.rows);  // ping -> pong
  push.source = 1;
  for (uint32_t i = 0; i < options_.iterations; ++i) {
    push.step = 1u << i;
    dispatch(cmd, *passes_[kAtrous], push, push.rows);
    push.source ^= 1u;
  }
  dispatch(cmd, *passes_[kFinal], push, height_);  // every row: those not filtered are copied
}

void Denoiser::recordCompileOnly(VkCommandBuffer cmd) const {
  gpu::DenoisePush push{};
  push.imageSize = glm::uvec2(1, 1);
  push.rows = 1;
  push.step = 1;
  for (const auto& p : passes_) {
    p->bind(cmd);
    p->push(cmd, push);
    p->dispatch(cmd, 1, 1);
    vk::memoryBarrier(cmd);
  }
}

}  // namespace wb::render
