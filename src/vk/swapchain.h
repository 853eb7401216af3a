// A window surface's swapchain: images, views, the render pass that draws into them and its framebuffers.
// Recreated on resize or vsync change; the render pass survives recreation (the surface format is fixed).
#pragma once
#include <optional>
#include <vector>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::vk {

class Swapchain {
 public:
  // Takes ownership of `surface`. Prefers a UNORM BGRA/RGBA format (the display shader encodes sRGB, so
  // ImGui's colours stay right); falls back to the surface's first format.
  Swapchain(Context& ctx, VkSurfaceKHR surface);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // (Re)creates the swapchain for a framebuffer size. Returns false when the size is zero (minimised).
  bool recreate(uint32_t width, uint32_t height, bool vsync);

  // Returns the acquired image index, or nullopt when the swapchain is out of date (call recreate).
  std::optional<uint32_t> acquire(VkSemaphore signal);
  // Presents; returns false when the swapchain is out of date or suboptimal (call recreate).
  bool present(uint32_t index, VkSemaphore wait);

  VkSwapchainKHR handle() const { return swapchain_; }
  VkRenderPass renderPass() const { return renderPass_; }
  VkFormat format() const { return format_.format; }
  bool formatIsSrgb() const;
  VkExtent2D extent() const { return extent_; }
  VkPresentModeKHR presentMode() const { return presentMode_; }
  uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
  uint32_t minImageCount() const { return minImageCount_; }
  VkImage image(uint32_t i) const { return images_.at(i); }
  VkFramebuffer framebuffer(uint32_t i) const { return framebuffers_.at(i); }
  // One semaphore per image for "rendering finished, present may start".
  VkSemaphore renderFinished(uint32_t i) const { return renderFinished_.at(i); }
  bool canReadBack() const { return transferSrc_; }

 private:
  void destroyImages();

  Context& ctx_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkSurfaceFormatKHR format_{};
  VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
  VkExtent2D extent_{};
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  uint32_t minImageCount_ = 2;
  bool transferSrc_ = false;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> renderFinished_;
};

// The present mode for a vsync choice: FIFO when on; MAILBOX, else IMMEDIATE, else FIFO when off.
VkPresentModeKHR choosePresentMode(const std::vector<VkPresentModeKHR>& available, bool vsync);
const char* presentModeName(VkPresentModeKHR mode);

}  // namespace wb::vk
