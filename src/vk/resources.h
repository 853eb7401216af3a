// Buffers and images with their own memory (one allocation each: scenes here have few, large resources).
#pragma once
#include <cstring>
#include <vector>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::vk {

constexpr uint64_t alignUp(uint64_t value, uint64_t alignment) {
  return alignment == 0 ? value : (value + alignment - 1) / alignment * alignment;
}

class Buffer {
 public:
  Buffer() = default;
  // Host-visible buffers are persistently mapped; device-local ones are filled through upload().
  Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);
  ~Buffer() { reset(); }
  Buffer(Buffer&& o) noexcept { *this = std::move(o); }
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  void reset();
  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  VkDeviceAddress address() const { return address_; }
  void* mapped() const { return mapped_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

  // Copies bytes into the buffer (directly when mapped, else through a staging buffer).
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);
  template <typename T>
  void upload(const std::vector<T>& v) {
    upload(v.data(), v.size() * sizeof(T));
  }
  // Reads bytes back (directly when mapped, else through a staging buffer).
  void download(void* data, VkDeviceSize bytes, VkDeviceSize offset = 0) const;

 private:
  Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  void* mapped_ = nullptr;
};

// Creates a device buffer holding `data` (usage gets TRANSFER_DST and, when asked, device address).
template <typename T>
Buffer makeBuffer(Context& ctx, const std::vector<T>& data, VkBufferUsageFlags usage) {
  VkDeviceSize size = std::max<VkDeviceSize>(data.size() * sizeof(T), 16);
  Buffer b(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
  if (!data.empty()) b.upload(data.data(), data.size() * sizeof(T));
  return b;
}

class Image {
 public:
  Image() = default;
  Image(Context& ctx, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
        uint32_t mipLevels = 1);
  ~Image() { reset(); }
  Image(Image&& o) noexcept { *this = std::move(o); }
  Image& operator=(Image&& o) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  void reset();
  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return format_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

  // Fills mip 0 with tightly packed pixels and leaves the image in `finalLayout`.
  void upload(const void* pixels, VkDeviceSize bytes, VkImageLayout finalLayout);
  // Reads mip 0 back (image must be in `layout`, it is returned to it).
  std::vector<uint8_t> download(VkImageLayout layout) const;

 private:
  Context* ctx_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  uint32_t width_ = 0, height_ = 0;
};

uint32_t formatBytes(VkFormat format);

// A full-image layout transition with conservative (all commands) synchronisation.
void transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT);
// A global memory barrier between all commands (used between dispatches that share buffers).
void memoryBarrier(VkCommandBuffer cmd);

}  // namespace wb::vk
