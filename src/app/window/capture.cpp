#include "app/window/capture.h"

#include <stdexcept>

#include "eval/image.h"

namespace wb::app {

void SwapchainCapture::record(VkCommandBuffer cmd, const vk::Swapchain& swapchain, uint32_t index) {
  if (!swapchain.canReadBack()) throw std::runtime_error("the swapchain images cannot be read back");
  width_ = swapchain.extent().width;
  height_ = swapchain.extent().height;
  format_ = swapchain.format();
  const VkDeviceSize bytes = VkDeviceSize(width_) * height_ * 4;
  if (!buffer_ || buffer_.size() < bytes) {
    buffer_ = vk::Buffer(ctx_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
  }
  VkImage image = swapchain.image(index);
  vk::transition(cmd, image, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {width_, height_, 1};
  vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_.handle(), 1, &region);
  vk::transition(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
}

void SwapchainCapture::write(const std::filesystem::path& path) const {
  if (!buffer_) throw std::runtime_error("no window image was captured");
  std::vector<uint8_t> rgba(size_t(width_) * height_ * 4);
  std::memcpy(rgba.data(), buffer_.mapped(), rgba.size());
  const bool bgr = format_ == VK_FORMAT_B8G8R8A8_UNORM || format_ == VK_FORMAT_B8G8R8A8_SRGB;
  for (size_t i = 0; i < rgba.size(); i += 4) {
    if (bgr) std::swap(rgba[i], rgba[i + 2]);
    rgba[i + 3] = 255;
  }
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  eval::writePng8(path, width_, height_, rgba);
}

}  // namespace wb::app
