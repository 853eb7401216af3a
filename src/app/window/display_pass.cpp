#include "app/window/display_pass.h"

#include "common/paths.h"

namespace wb::app {
namespace {

render::GraphicsRecipe displayRecipe(VkRenderPass renderPass, VkFormat format) {
  render::GraphicsRecipe g;
  g.desc.renderPass = renderPass;
  g.desc.colorFormats = {format};
  return g;
}

}  // namespace

std::vector<shader::ShaderKey> DisplayPass::stageKeys() {
  const auto dir = shaderDir() / "display";
  return {{dir / "fullscreen.vert", std::nullopt, {}}, {dir / "display.frag", std::nullopt, {}}};
}

DisplayPass::DisplayPass(vk::Context& ctx, shader::ShaderLibrary& library, VkRenderPass renderPass,
                         VkFormat format)
    : pass_(ctx, library, "display", displayRecipe(renderPass, format)) {
  pass_.setPushConstantBytes(sizeof(gpu::DisplayPush));
  pass_.useProgram("display", stageKeys());
  setSources({});
  pass_.rebuild();
}

void DisplayPass::setSources(const DisplaySources& sources) {
  if (sources == sources_ && sources.accum) return;
  sources_ = sources;
  pass_.setStorageImage("accumImage", sources_.accum);
  pass_.setStorageImage("albedoImage", sources_.albedo);
  pass_.setStorageImage("normalImage", sources_.normal);
  pass_.setStorageImage("infoImage", sources_.info);
  pass_.setStorageImage("previewImage", sources_.preview);
  pass_.setStorageImage("statsImage", sources_.stats);
  pass_.setStorageImage("costImage", sources_.cost);
  pass_.setStorageImage("denoisedImage", sources_.denoised ? sources_.denoised : sources_.accum);
}

void DisplayPass::record(VkCommandBuffer cmd, const gpu::DisplayPush& push) const {
  VkViewport vp{push.viewRect.x, push.viewRect.y, push.viewRect.z, push.viewRect.w, 0.0f, 1.0f};
  VkRect2D scissor{{int32_t(push.viewRect.x), int32_t(push.viewRect.y)},
                   {uint32_t(push.viewRect.z), uint32_t(push.viewRect.w)}};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  pass_.bind(cmd);
  pass_.push(cmd, push);
  vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace wb::app
