#include "render/denoiser.h"

#include <algorithm>
#include <cstring>

#include "common/env.h"
#include "common/paths.h"

namespace wb::render {
namespace {

constexpr uint32_t kGroupSize = WB_DENOISE_GROUP_SIZE;  // local_size of shaders/denoise/*.comp
const char* const kPassNames[] = {"denoise prepare (compute)", "denoise variance (compute)",
                                  "denoise a-trous (compute)", "denoise final (compute)",
                                  "denoise gain (compute)",    "denoise scale (compute)"};
const char* const kProgramNames[] = {"denoise-prepare", "denoise-variance", "denoise-atrous",
                                     "denoise-final",   "denoise-gain",     "denoise-scale"};
const char* const kTimerKeys[] = {"denoise_prepare", "denoise_variance", "denoise_atrous",
                                  "denoise_final",   "denoise_gain",     "denoise_scale"};
const char* const kFiles[] = {"prepare.comp", "variance.comp", "atrous.comp",
                              "final.comp",   "gain.comp",     "scale.comp"};

uint32_t groups(uint32_t pixels) {
  return (pixels + kGroupSize - 1) / kGroupSize;
}

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
  options_.window = env::choice("WB_DENOISE_WINDOW").value_or(true);
  resize(1, 1);
  for (auto& p : passes_) p->rebuild();
}

Denoiser::~Denoiser() {
  ctx_.waitIdle();
  for (auto& p : passes_) p.reset();
}

void Denoiser::resize(uint32_t width, uint32_t height) {
  width_ = std::max(width, 1u);
  height_ = std::max(height, 1u);
  // The images only grow: the window's preview levels and resizes come back to sizes already held.
  if (width_ <= capacityWidth_ && height_ <= capacityHeight_) return;
  width = capacityWidth_ = std::max(width_, capacityWidth_);
  height = capacityHeight_ = std::max(height_, capacityHeight_);
  ctx_.waitIdle();
  inputs_ = {};  // the caller's images may have been remade with the size: setInputs() binds them again
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                  VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  output_ = vk::Image(ctx_, width, height, VK_FORMAT_R32G32B32A32_SFLOAT, usage);
  const VkDeviceSize pixels = VkDeviceSize(width) * height;
  const VkBufferUsageFlags bufferUsage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;  // vk::Buffer adds the address
  geometry_ = vk::Buffer(ctx_, pixels * 4 * sizeof(float), bufferUsage, false);
  filter_ = vk::Buffer(ctx_, 2 * pixels * 4 * sizeof(float), bufferUsage, false);  // two planes
  gradient_ = vk::Buffer(ctx_, pixels * sizeof(float), bufferUsage, false);
  handover_ = vk::Buffer(ctx_, pixels * 4 * sizeof(float), bufferUsage, false);
  bias_ = vk::Buffer(ctx_, pixels * sizeof(float), bufferUsage, false);
  const VkDeviceSize tiles = VkDeviceSize(groups(width)) * groups(height);
  tiles_ = vk::Buffer(ctx_, tiles * 2 * 4 * sizeof(float), bufferUsage, false);
  gains_ = vk::Buffer(ctx_, tiles * 4 * sizeof(float), bufferUsage, false);
  ctx_.submitAndWait([&](VkCommandBuffer cmd) {
    vk::transition(cmd, output_.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    VkClearColorValue zero{};
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, output_.handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    for (const vk::Buffer* b : {&geometry_, &filter_, &gradient_, &handover_, &bias_, &tiles_, &gains_})
      vkCmdFillBuffer(cmd, b->handle(), 0, VK_WHOLE_SIZE, 0);
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
    p->setStorageImage("outputImage", output_.view());
  }
}

std::vector<float> Denoiser::readOutput() const {
  const auto bytes = output_.download(VK_IMAGE_LAYOUT_GENERAL);
  std::vector<float> rgba(size_t(width_) * height_ * 4);
  const size_t row = size_t(width_) * 4 * sizeof(float), stride = size_t(capacityWidth_) * 4 * sizeof(float);
  for (uint32_t y = 0; y < height_; ++y)
    std::memcpy(reinterpret_cast<char*>(rgba.data()) + y * row, bytes.data() + y * stride, row);
  return rgba;
}

std::vector<Pass*> Denoiser::passes() const {
  std::vector<Pass*> out;
  for (const auto& p : passes_) out.push_back(p.get());
  return out;
}

void Denoiser::dispatch(VkCommandBuffer cmd, size_t pass, const gpu::DenoisePush& push, uint32_t rows,
                        vk::GpuTimer* perPass) const {
  vk::GpuTimer::Scope scope(perPass, cmd, kTimerKeys[pass]);
  passes_[pass]->bind(cmd);
  passes_[pass]->push(cmd, push);
  passes_[pass]->dispatch(cmd, groups(width_), groups(rows));
  vk::memoryBarrier(cmd);
}

gpu::DenoisePush Denoiser::basePush() const {
  const auto address = [](const vk::Buffer& b) {
    return glm::uvec2(uint32_t(b.address()), uint32_t(b.address() >> 32));
  };
  gpu::DenoisePush push{};
  push.imageSize = glm::uvec2(width_, height_);
  push.buffers.geometry = address(geometry_);
  push.buffers.filtered = address(filter_);
  push.buffers.gradient = address(gradient_);
  push.buffers.handover = address(handover_);
  push.buffers.bias = address(bias_);
  push.buffers.tiles = address(tiles_);
  push.buffers.gain = address(gains_);
  return push;
}

void Denoiser::record(VkCommandBuffer cmd, uint32_t rows, vk::GpuTimer* perPass) const {
  gpu::DenoisePush push = basePush();
  push.rows = std::min(rows, height_);
  push.sigmaLuminance = options_.sigmaLuminance;
  push.sigmaNormal = options_.sigmaNormal;
  push.sigmaDepth = options_.sigmaDepth;
  push.handoverTau = options_.handoverTau;
  push.window = options_.window ? 1u : 0u;
  vk::memoryBarrier(cmd);  // the path tracer's writes before the first read
  dispatch(cmd, kPrepare, push, push.rows, perPass);
  dispatch(cmd, kVariance, push, push.rows, perPass);  // filter plane 0 -> 1
  push.source = 1;
  // At least one iteration: the last one leaves the bias the final pass reads.
  const uint32_t iterations = std::max(options_.iterations, 1u);
  for (uint32_t i = 0; i < iterations; ++i) {
    push.step = 1u << i;
    push.last = i + 1 == iterations ? 1u : 0u;
    dispatch(cmd, kAtrous, push, push.rows, perPass);
    push.source ^= 1u;
  }
  dispatch(cmd, kFinal, push, height_, perPass);  // every row: those not filtered are copied
  if (!options_.window) return;
  // One invocation per 8x8 group of the final pass.
  {
    vk::GpuTimer::Scope scope(perPass, cmd, kTimerKeys[kGain]);
    passes_[kGain]->bind(cmd);
    for (uint32_t phase = 0; phase < 2; ++phase) {
      push.step = phase;
      passes_[kGain]->push(cmd, push);
      passes_[kGain]->dispatch(cmd, groups(groups(width_)), groups(groups(height_)));
      vk::memoryBarrier(cmd);
    }
  }
  dispatch(cmd, kScale, push, height_, perPass);
}

void Denoiser::recordCompileOnly(VkCommandBuffer cmd) const {
  gpu::DenoisePush push = basePush();  // the buffers hold at least the one pixel
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
