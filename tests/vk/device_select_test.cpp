#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include "vk/device_select.h"

using namespace wb::vk;

namespace {

DeviceCandidate device(std::string name, bool discrete, bool cpu, std::vector<std::string> ext,
                       uint32_t api = VK_API_VERSION_1_3) {
  DeviceCandidate c;
  c.name = std::move(name);
  c.discrete = discrete;
  c.cpu = cpu;
  c.extensions = std::move(ext);
  c.apiVersion = api;
  return c;
}

const std::vector<std::string>& rt() {
  return requiredDeviceExtensions();
}

}  // namespace

TEST(DeviceSelect, PrefersDiscreteGpu) {
  auto choice =
      chooseDevice({device("llvmpipe", false, true, rt()), device("NVIDIA H100", true, false, rt())}, rt());
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 1u);
}

TEST(DeviceSelect, FallsBackToLavapipe) {
  auto choice = chooseDevice(
      {device("llvmpipe", false, true, rt()), device("Old GPU", true, false, {"VK_KHR_swapchain"})}, rt());
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 0u);
}

TEST(DeviceSelect, NameOverrideWins) {
  auto choice = chooseDevice(
      {device("llvmpipe", false, true, rt()), device("NVIDIA H100", true, false, rt())}, rt(), "LLVMpipe");
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 0u);
}

TEST(DeviceSelect, NoQualifyingDeviceNamesDevicesAndMissingExtensions) {
  // Mesa 22.3's lavapipe: no ray tracing.
  auto choice = chooseDevice({device("llvmpipe (LLVM 15)", false, true, {"VK_KHR_swapchain"})}, rt());
  EXPECT_FALSE(choice.index);
  EXPECT_NE(choice.error.find("llvmpipe (LLVM 15)"), std::string::npos) << choice.error;
  EXPECT_NE(choice.error.find("VK_KHR_ray_tracing_pipeline"), std::string::npos) << choice.error;
  EXPECT_NE(choice.error.find("VK_KHR_acceleration_structure"), std::string::npos) << choice.error;
  EXPECT_NE(choice.error.find("Mesa >= 24.1"), std::string::npos) << choice.error;
}

TEST(DeviceSelect, OldApiVersionDoesNotQualify) {
  auto choice = chooseDevice({device("ancient", true, false, rt(), VK_API_VERSION_1_1)}, rt());
  EXPECT_FALSE(choice.index);
  EXPECT_NE(choice.error.find("Vulkan 1.3"), std::string::npos) << choice.error;
  auto onePointTwo = chooseDevice({device("older", true, false, rt(), VK_API_VERSION_1_2)}, rt());
  EXPECT_FALSE(onePointTwo.index) << "dynamic rendering and synchronization2 are Vulkan 1.3";
}

TEST(DeviceSelect, AGpuLackingAFeatureFallsBackToLavapipeAndIsNamed) {
  auto gpu = device("Some GPU", true, false, rt());
  gpu.missingFeatures = {"scalarBlockLayout"};
  auto choice = chooseDevice({gpu, device("llvmpipe", false, true, rt())}, rt());
  ASSERT_TRUE(choice.index);
  EXPECT_EQ(*choice.index, 1u);
  auto none = chooseDevice({gpu}, rt());
  EXPECT_FALSE(none.index);
  EXPECT_NE(none.error.find("feature scalarBlockLayout"), std::string::npos) << none.error;
}

TEST(DeviceSelect, UnknownOverrideIsReported) {
  auto choice = chooseDevice({device("llvmpipe", false, true, rt())}, rt(), "radeon");
  EXPECT_FALSE(choice.index);
  EXPECT_NE(choice.error.find("--device 'radeon'"), std::string::npos) << choice.error;
  EXPECT_NE(choice.error.find("llvmpipe"), std::string::npos) << choice.error;
}

TEST(DeviceSelect, NoDevicesAtAll) {
  auto choice = chooseDevice({}, rt());
  EXPECT_FALSE(choice.index);
  EXPECT_NE(choice.error.find("no Vulkan devices"), std::string::npos);
}
