// The environment on the device: an RGBA32F equirectangular image (1x1 for a constant colour) and the alias
// table that importance-samples it.
#pragma once
#include <string>
#include <vector>

#include "shared/gpu_types.h"
#include "vk/resources.h"

namespace wb::render {

struct EnvironmentData {
  uint32_t width = 1, height = 1;
  std::vector<float> rgb;  // width * height * 3, row 0 = top (+Y)
  std::vector<gpu::EnvAliasEntry> alias;
  float totalWeight = 0.0f;
  bool isMap = false;                 // false: a constant colour
  std::vector<std::string> warnings;  // the loader's (an 8-bit image taken as radiance)
};

class GpuEnvironment {
 public:
  GpuEnvironment(vk::Context& ctx, const EnvironmentData& data);
  ~GpuEnvironment();
  GpuEnvironment(const GpuEnvironment&) = delete;
  GpuEnvironment& operator=(const GpuEnvironment&) = delete;

  VkDescriptorImageInfo descriptor() const {
    return {sampler_, image_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  }
  const vk::Buffer& aliasTable() const { return alias_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  float totalWeight() const { return totalWeight_; }
  bool isMap() const { return isMap_; }

 private:
  vk::Context& ctx_;
  vk::Image image_;
  vk::Buffer alias_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  uint32_t width_ = 1, height_ = 1;
  float totalWeight_ = 0.0f;
  bool isMap_ = false;
};

}  // namespace wb::render
