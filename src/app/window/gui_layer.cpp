#include "app/window/gui_layer.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include "vk/swapchain.h"

namespace wb::app {
namespace {

void checkVk(VkResult r) {
  if (r != VK_SUCCESS) vk::throwVkError(r, "imgui vulkan backend", __FILE__, __LINE__);
}

void applyStyle() {
  ImGui::StyleColorsDark();
  ImGuiStyle& s = ImGui::GetStyle();
  s.WindowRounding = 0.0f;
  s.FrameRounding = 3.0f;
  s.GrabRounding = 3.0f;
  s.WindowBorderSize = 0.0f;
  s.ItemSpacing = ImVec2(6, 4);
  s.Colors[ImGuiCol_WindowBg] = ImVec4(0.11f, 0.12f, 0.14f, 1.0f);
}

}  // namespace

GuiLayer::GuiLayer(vk::Context& ctx, GLFWwindow* window, const vk::Swapchain& swapchain, std::string iniPath)
    : ctx_(ctx), iniPath_(std::move(iniPath)) {
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 64}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pi.maxSets = 64;
  pi.poolSizeCount = 1;
  pi.pPoolSizes = sizes;
  WB_VK(vkCreateDescriptorPool(ctx.device(), &pi, nullptr, &pool_));

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  // No imgui.ini next to the user's files unless asked for (--imgui-ini keeps the panel layout there).
  io.IniFilename = iniPath_.empty() ? nullptr : iniPath_.c_str();
  io.LogFilename = nullptr;
  applyStyle();
  ImGui_ImplGlfw_InitForVulkan(window, true);
  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = ctx.instance();
  info.PhysicalDevice = ctx.physicalDevice();
  info.Device = ctx.device();
  info.QueueFamily = ctx.queueFamily();
  info.Queue = ctx.queue();
  info.DescriptorPool = pool_;
  info.Subpass = 0;
  info.MinImageCount = swapchain.minImageCount();
  info.ImageCount = swapchain.imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkVk;
  ImGui_ImplVulkan_Init(&info, swapchain.renderPass());
  ctx.submitAndWait([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

GuiLayer::~GuiLayer() {
  ctx_.waitIdle();
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  vkDestroyDescriptorPool(ctx_.device(), pool_, nullptr);
}

void GuiLayer::swapchainRecreated(const vk::Swapchain& swapchain) {
  ImGui_ImplVulkan_SetMinImageCount(swapchain.minImageCount());
}

void GuiLayer::beginFrame() {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void GuiLayer::render(VkCommandBuffer cmd) {
  ImGui::Render();
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
}

}  // namespace wb::app
