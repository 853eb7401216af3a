// The denoiser: an edge-avoiding, variance-guided a-trous filter (the spatial filter of SVGF) over the path
// tracer's accumulation, as compute passes. Guided by the first-hit albedo, normal and depth AOVs and the
// per-pixel luminance variance the path tracer keeps (its stats AOV), it filters the radiance demodulated by
// the albedo over a fixed number of iterations with growing steps, modulates it again, and hands over to the
// raw mean as the mean becomes precise (shaders/denoise/final.comp): its strength follows the variance of the
// accumulated mean, so a converged image is the path tracer's own. docs/reports/denoiser.md measures it.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>
#include <vulkan/vulkan.h>

#include "render/pass.h"
#include "vk/gpu_timer.h"
#include "shared/denoise_types.h"

namespace wb::render {

struct DenoiseOptions {
  uint32_t iterations = 4;      // a-trous iterations (at least 1); the step doubles each time (1, 2, 4, 8)
  float sigmaLuminance = 4.0f;  // luminance edge-stopping in standard deviations of the mean; 0: off
  float sigmaNormal = 128.0f;   // exponent of the normals' cosine
  float sigmaDepth = 1.0f;      // depth edge-stopping, in multiples of the depth change per pixel
  float handoverTau = 0.1f;     // relative error assumed for the filtered image; < 0: no hand-over (tests)
  // The output's radiance made the raw image's over 40x40-pixel windows (shaders/denoise/gain.comp): what the
  // filter takes from fireflies goes back to their surroundings. WB_DENOISE_WINDOW=0 turns it off.
  bool window = true;
};

// The images the denoiser reads (the path tracer's, GENERAL layout): radiance rgba32f with the samples per
// pixel in alpha, albedo and normal/depth rgba16f, stats rgba32f (r = mean luminance^2).
struct DenoiseInputs {
  VkImageView radiance = VK_NULL_HANDLE, albedo = VK_NULL_HANDLE, normal = VK_NULL_HANDLE,
              stats = VK_NULL_HANDLE;
};

class Denoiser {
 public:
  Denoiser(vk::Context& ctx, shader::ShaderLibrary& library);
  ~Denoiser();
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;

  // The shader stage of each pass, in passes() order.
  static std::vector<shader::ShaderKey> stageKeys();

  // Size of the images it filters (its own buffers and image grow to the largest size asked; no work may be
  // in flight when they grow); then the inputs (call both when no work is in flight).
  void resize(uint32_t width, uint32_t height);
  void setInputs(const DenoiseInputs& inputs);
  void setOptions(const DenoiseOptions& options) { options_ = options; }
  const DenoiseOptions& options() const { return options_; }

  // Records every pass into cmd, barriers included: output() then holds the denoised radiance (alpha: the
  // samples per pixel, as the input). Only rows [0, rows) are read and filtered; the others are copied.
  // With a timer, each pass is a scope of its own (its key: "denoise_" and the pass: prepare, variance,
  // atrous (the iterations summed), final, gain, scale); the caller then records no scope around it.
  void record(VkCommandBuffer cmd, uint32_t rows = ~0u, vk::GpuTimer* perPass = nullptr) const;
  // Each pass over one workgroup (a driver that compiles at the first dispatch compiles them).
  void recordCompileOnly(VkCommandBuffer cmd) const;
  // The output image (at least width() x height(): read pixels [0, width()) x [0, height()) of it) and those
  // pixels read back (RGBA, rows of width(); waits for the device).
  const vk::Image& output() const { return output_; }
  std::vector<float> readOutput() const;
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

  // prepare, variance, a-trous, final, gain, scale.
  std::vector<Pass*> passes() const;

 private:
  enum { kPrepare, kVariance, kAtrous, kFinal, kGain, kScale, kPassCount };
  void bind();
  // The push constants every pass starts from: the image's size and the buffers' addresses.
  gpu::DenoisePush basePush() const;
  void dispatch(VkCommandBuffer cmd, size_t pass, const gpu::DenoisePush& push, uint32_t rows,
                vk::GpuTimer* perPass) const;

  vk::Context& ctx_;
  std::array<std::unique_ptr<Pass>, kPassCount> passes_;
  DenoiseOptions options_;
  uint32_t width_ = 0, height_ = 0, capacityWidth_ = 0, capacityHeight_ = 0;
  DenoiseInputs inputs_;
  // The intermediates, buffers of a pixel per element reached by device address
  // (shaders/shared/denoise_types.h): a CPU driver gathers from an address for less than from a storage
  // buffer, and for much less than it loads from an image.
  vk::Buffer geometry_, filter_, gradient_, handover_, bias_, tiles_, gains_;
  vk::Image output_;
};

}  // namespace wb::render
