// The display pass: a fullscreen triangle whose fragment shader reads the path tracer's accumulation and AOV
// images and applies exposure, a tonemapper and sRGB (shaders/display/). Its layout is reflected from the
// shaders; like the renderers it hot reloads in two steps (build off the frame path, install at a frame
// boundary), so a broken edit keeps the last good pipeline on screen.
#pragma once
#include <memory>

#include "display/display_types.h"
#include "shader/library.h"
#include "vk/built_pipeline.h"

namespace wb::app {

// The storage images the display reads (all in GENERAL layout).
struct DisplaySources {
  VkImageView accum = VK_NULL_HANDLE, albedo = VK_NULL_HANDLE, normal = VK_NULL_HANDLE, info = VK_NULL_HANDLE,
              preview = VK_NULL_HANDLE, stats = VK_NULL_HANDLE;
  bool operator==(const DisplaySources&) const = default;
};

class DisplayPass {
 public:
  DisplayPass(vk::Context& ctx, shader::ShaderLibrary& library, VkRenderPass renderPass);
  ~DisplayPass();
  DisplayPass(const DisplayPass&) = delete;
  DisplayPass& operator=(const DisplayPass&) = delete;

  static std::vector<shader::ShaderKey> stageKeys();
  shader::ShaderLibrary::ProgramId program() const { return program_; }

  std::unique_ptr<vk::BuiltPipeline> build(const shader::ShaderLibrary::ProgramBuild& build) const;
  void install(std::unique_ptr<vk::BuiltPipeline> pipeline);  // waits for the device

  // Rewrites the descriptors when an image changed (call between frames, when the last frame finished).
  void setSources(const DisplaySources& sources);
  // Records the draw into the current render pass, with the viewport set to the image's rectangle.
  void record(VkCommandBuffer cmd, const gpu::DisplayPush& push) const;

 private:
  void writeDescriptors(vk::DescriptorSets& s);

  vk::Context& ctx_;
  VkRenderPass renderPass_;
  shader::ShaderLibrary::ProgramId program_ = 0;
  std::unique_ptr<vk::BuiltPipeline> current_;
  std::unique_ptr<vk::DescriptorSets> sets_;
  std::vector<vk::ProvidedBinding> provided_;  // what writeDescriptors fills: a program may use no more
  DisplaySources sources_;
};

}  // namespace wb::app
