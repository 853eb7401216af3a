#include "vk/pipeline_cache.h"

#include <cstring>
#include <fstream>
#include <iterator>
#include <unistd.h>
#include <vector>

#include "common/atomic_file.h"
#include "common/file_io.h"
#include "vk/check.h"

namespace wb::vk {

bool PipelineCache::headerMatches(const void* data, size_t size, const VkPhysicalDeviceProperties& props) {
  if (size < sizeof(VkPipelineCacheHeaderVersionOne)) return false;
  VkPipelineCacheHeaderVersionOne h;
  std::memcpy(&h, data, sizeof(h));
  return h.headerSize >= sizeof(h) && h.headerSize <= size &&
         h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && h.vendorID == props.vendorID &&
         h.deviceID == props.deviceID &&
         std::memcmp(h.pipelineCacheUUID, props.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& props,
                             std::filesystem::path file)
    : device_(device), props_(props), file_(std::move(file)) {
  std::vector<char> data;
  if (!file_.empty()) {
    // Non-blocking and regular files only: a named pipe in the cache folder must not stall start-up.
    if (auto bytes = readRegularFile(file_, nullptr, uint64_t{1} << 30))
      data.assign(bytes->begin(), bytes->end());
    if (!data.empty() && !headerMatches(data.data(), data.size(), props)) {
      warning_ =
          "pipeline cache " + file_.string() + " is for another device or driver, or corrupt: starting empty";
      data.clear();
    }
  }
  VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  ci.initialDataSize = data.size();
  ci.pInitialData = data.empty() ? nullptr : data.data();
  if (vkCreatePipelineCache(device_, &ci, nullptr, &cache_) != VK_SUCCESS) {
    // A driver that rejects the data: start empty.
    warning_ = "pipeline cache " + file_.string() + " rejected by the driver: starting empty";
    ci.initialDataSize = 0;
    ci.pInitialData = nullptr;
    WB_VK(vkCreatePipelineCache(device_, &ci, nullptr, &cache_));
  } else {
    loadedBytes_ = data.size();
  }
}

PipelineCache::~PipelineCache() {
  if (cache_) {
    save();
    vkDestroyPipelineCache(device_, cache_, nullptr);
  }
}

bool PipelineCache::save() {
  if (file_.empty() || !cache_) return false;
  size_t size = 0;
  if (vkGetPipelineCacheData(device_, cache_, &size, nullptr) != VK_SUCCESS || size == 0) return false;
  std::vector<char> data(size);
  if (vkGetPipelineCacheData(device_, cache_, &size, data.data()) != VK_SUCCESS) return false;
  std::error_code ec;
  std::filesystem::create_directories(file_.parent_path(), ec);
  try {
    writeFileAtomically(file_, std::string_view(data.data(), size), "pipeline cache", FileKind::Cache);
  } catch (const std::exception& e) {
    warning_ = e.what();
    return false;
  }
  return true;
}

}  // namespace wb::vk
