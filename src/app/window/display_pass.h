// The display pass: a fullscreen triangle whose fragment shader reads the path tracer's accumulation and AOV
// images and applies exposure, a tonemapper and sRGB (shaders/display/). A render::Pass like the renderers'
// (reflected layout, resources by name, hot reloaded by the live-edit loop), drawn into the swapchain's
// render pass.
#pragma once
#include <memory>

#include "display/display_types.h"
#include "render/pass.h"
#include "shader/library.h"

namespace wb::app {

// The storage images the display reads (all in GENERAL layout).
struct DisplaySources {
  VkImageView accum = VK_NULL_HANDLE, albedo = VK_NULL_HANDLE, normal = VK_NULL_HANDLE, info = VK_NULL_HANDLE,
              preview = VK_NULL_HANDLE, stats = VK_NULL_HANDLE, cost = VK_NULL_HANDLE;
  VkImageView denoised = VK_NULL_HANDLE;  // null: the accumulation is bound in its place
  bool operator==(const DisplaySources&) const = default;
};

class DisplayPass {
 public:
  DisplayPass(vk::Context& ctx, shader::ShaderLibrary& library, VkRenderPass renderPass, VkFormat format);

  static std::vector<shader::ShaderKey> stageKeys();
  render::Pass& pass() { return pass_; }

  // Points the pass at other images (call between frames, when the last frame finished).
  void setSources(const DisplaySources& sources);
  // Records the draw into the current render pass, with the viewport set to the image's rectangle.
  void record(VkCommandBuffer cmd, const gpu::DisplayPush& push) const;

 private:
  render::Pass pass_;
  DisplaySources sources_;
};

}  // namespace wb::app
