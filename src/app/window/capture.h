// Saving what the workbench shows: the presented swapchain image (panel included) read back to a PNG, and the
// render itself as PNG (tonemapped) + EXR (linear) + a JSON sidecar with the parameters.
#pragma once
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "vk/resources.h"
#include "vk/swapchain.h"

namespace wb::app {

class SwapchainCapture {
 public:
  explicit SwapchainCapture(vk::Context& ctx) : ctx_(ctx) {}
  // Records a copy of swapchain image `index` (in PRESENT_SRC layout after the render pass) into a host
  // buffer.
  void record(VkCommandBuffer cmd, const vk::Swapchain& swapchain, uint32_t index);
  // After the frame's fence: writes the copied pixels as an RGB PNG.
  void write(const std::filesystem::path& path) const;

 private:
  vk::Context& ctx_;
  vk::Buffer buffer_;
  uint32_t width_ = 0, height_ = 0;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace wb::app
