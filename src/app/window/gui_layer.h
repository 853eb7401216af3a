// Dear ImGui on GLFW + Vulkan, drawing into the swapchain's render pass. No imgui.ini is read or written
// unless the user names one (--imgui-ini).
#pragma once
#include <string>

#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace wb::vk {
class Context;
class Swapchain;
}  // namespace wb::vk

namespace wb::app {

class GuiLayer {
 public:
  GuiLayer(vk::Context& ctx, GLFWwindow* window, const vk::Swapchain& swapchain, std::string iniPath = {});
  ~GuiLayer();
  GuiLayer(const GuiLayer&) = delete;
  GuiLayer& operator=(const GuiLayer&) = delete;

  void swapchainRecreated(const vk::Swapchain& swapchain);
  void beginFrame();
  void render(VkCommandBuffer cmd);  // ends the ImGui frame and records its draw data

 private:
  vk::Context& ctx_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::string iniPath_;  // ImGui keeps a pointer to it
};

}  // namespace wb::app
