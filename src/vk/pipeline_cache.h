// A VkPipelineCache persisted on disk (shader_cache/), so real GPUs skip the driver's compile of unchanged
// pipelines in a new process. lavapipe's cache data is only a header (its own disk cache does that job).
#pragma once
#include <filesystem>
#include <string>
#include <vulkan/vulkan.h>

namespace wb::vk {

class PipelineCache {
 public:
  // Loads `file` when its header matches this device (vendor, device, pipelineCacheUUID); otherwise starts
  // empty and says why in warning(). An empty path: a cache in memory only.
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& props, std::filesystem::path file);
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  // Writes the cache atomically (temp file + rename); false (with warning()) when it cannot.
  bool save();
  size_t loadedBytes() const { return loadedBytes_; }
  const std::string& warning() const { return warning_; }

  // True when `data` starts with a version-one header for this device.
  static bool headerMatches(const void* data, size_t size, const VkPhysicalDeviceProperties& props);

 private:
  VkDevice device_;
  VkPhysicalDeviceProperties props_;
  std::filesystem::path file_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  size_t loadedBytes_ = 0;
  std::string warning_;
};

}  // namespace wb::vk
