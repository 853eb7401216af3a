#include "vk/swapchain.h"

#include <algorithm>

namespace wb::vk {

VkPresentModeKHR choosePresentMode(const std::vector<VkPresentModeKHR>& available, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;
  for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
    if (std::find(available.begin(), available.end(), m) != available.end()) return m;
  }
  return VK_PRESENT_MODE_FIFO_KHR;
}

const char* presentModeName(VkPresentModeKHR mode) {
  switch (mode) {
    case VK_PRESENT_MODE_FIFO_KHR:
      return "FIFO (vsync)";
    case VK_PRESENT_MODE_MAILBOX_KHR:
      return "MAILBOX";
    case VK_PRESENT_MODE_IMMEDIATE_KHR:
      return "IMMEDIATE";
    case VK_PRESENT_MODE_FIFO_RELAXED_KHR:
      return "FIFO relaxed";
    default:
      return "other";
  }
}

Swapchain::Swapchain(Context& ctx, VkSurfaceKHR surface) : ctx_(ctx), surface_(surface) {
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physicalDevice(), ctx.queueFamily(), surface, &supported);
  if (!supported) throw VulkanError("the device's queue cannot present to this window surface");

  uint32_t count = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &count, formats.data());
  if (formats.empty()) throw VulkanError("the window surface has no formats");
  format_ = formats[0];
  for (const auto& f : formats) {
    if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
      format_ = f;
      break;
    }
  }

  VkAttachmentDescription color{};
  color.format = format_.format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &ref;
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  dep.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = 1;
  rp.pAttachments = &color;
  rp.subpassCount = 1;
  rp.pSubpasses = &subpass;
  rp.dependencyCount = 1;
  rp.pDependencies = &dep;
  WB_VK(vkCreateRenderPass(ctx.device(), &rp, nullptr, &renderPass_));
}

Swapchain::~Swapchain() {
  ctx_.waitIdle();
  destroyImages();
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  if (renderPass_) vkDestroyRenderPass(ctx_.device(), renderPass_, nullptr);
  if (surface_) vkDestroySurfaceKHR(ctx_.instance(), surface_, nullptr);
}

bool Swapchain::formatIsSrgb() const {
  return format_.format == VK_FORMAT_B8G8R8A8_SRGB || format_.format == VK_FORMAT_R8G8B8A8_SRGB;
}

void Swapchain::destroyImages() {
  VkDevice d = ctx_.device();
  for (auto f : framebuffers_) vkDestroyFramebuffer(d, f, nullptr);
  for (auto v : views_) vkDestroyImageView(d, v, nullptr);
  for (auto s : renderFinished_) vkDestroySemaphore(d, s, nullptr);
  framebuffers_.clear();
  views_.clear();
  renderFinished_.clear();
  images_.clear();
}

bool Swapchain::recreate(uint32_t width, uint32_t height, bool vsync) {
  VkSurfaceCapabilitiesKHR caps{};
  WB_VK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physicalDevice(), surface_, &caps));
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {
    extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0 || width == 0 || height == 0) return false;

  uint32_t count = 0;
  vkGetPhysicalDeviceSurfacePresentModesKHR(ctx_.physicalDevice(), surface_, &count, nullptr);
  std::vector<VkPresentModeKHR> modes(count);
  vkGetPhysicalDeviceSurfacePresentModesKHR(ctx_.physicalDevice(), surface_, &count, modes.data());
  presentMode_ = choosePresentMode(modes, vsync);

  ctx_.waitIdle();
  destroyImages();
  minImageCount_ = std::max(caps.minImageCount, 2u);
  uint32_t imageCount = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
  transferSrc_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = imageCount;
  ci.imageFormat = format_.format;
  ci.imageColorSpace = format_.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                  (transferSrc_ ? VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_SRC_BIT) : VkImageUsageFlags(0));
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  const uint32_t alphaModes = caps.supportedCompositeAlpha;
  ci.compositeAlpha = (alphaModes & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : static_cast<VkCompositeAlphaFlagBitsKHR>(alphaModes & (~alphaModes + 1u));
  ci.presentMode = presentMode_;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = swapchain_;
  VkSwapchainKHR created = VK_NULL_HANDLE;
  WB_VK(vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &created));
  if (swapchain_) vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  swapchain_ = created;
  extent_ = extent;

  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &count, nullptr);
  images_.resize(count);
  vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &count, images_.data());
  for (VkImage image : images_) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = format_.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    WB_VK(vkCreateImageView(ctx_.device(), &vi, nullptr, &view));
    views_.push_back(view);
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = renderPass_;
    fi.attachmentCount = 1;
    fi.pAttachments = &view;
    fi.width = extent.width;
    fi.height = extent.height;
    fi.layers = 1;
    VkFramebuffer fb = VK_NULL_HANDLE;
    WB_VK(vkCreateFramebuffer(ctx_.device(), &fi, nullptr, &fb));
    framebuffers_.push_back(fb);
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s = VK_NULL_HANDLE;
    WB_VK(vkCreateSemaphore(ctx_.device(), &si, nullptr, &s));
    renderFinished_.push_back(s);
  }
  return true;
}

std::optional<uint32_t> Swapchain::acquire(VkSemaphore signal) {
  uint32_t index = 0;
  VkResult r = vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, signal, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) return std::nullopt;
  if (r != VK_SUBOPTIMAL_KHR) WB_VK(r);
  return index;
}

bool Swapchain::present(uint32_t index, VkSemaphore wait) {
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &wait;
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  VkResult r;
  {
    std::lock_guard lock(ctx_.queueMutex());
    r = vkQueuePresentKHR(ctx_.queue(), &pi);
  }
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR) return false;
  WB_VK(r);
  return true;
}

}  // namespace wb::vk
