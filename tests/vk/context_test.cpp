// The real device on this machine (lavapipe here, a GPU where there is one), under the validation layer.
#include <gtest/gtest.h>

#include "vk/context.h"

using namespace wb::vk;

TEST(Context, CreatesRayTracingDeviceWithValidation) {
  ContextOptions o;
  o.validation = true;
  Context ctx(o);
  EXPECT_FALSE(ctx.deviceName().empty());
  EXPECT_GT(ctx.rayTracing().handleSize, 0u);
  EXPECT_GE(ctx.rayTracing().maxRecursionDepth, 2u);
  ctx.submitAndWait([](VkCommandBuffer) {});
  EXPECT_EQ(ctx.validationErrors(), 0u);
}

TEST(Context, UnknownDeviceNameIsAClearError) {
  ContextOptions o;
  o.deviceName = "no-such-gpu-xyz";
  try {
    Context ctx(o);
    FAIL() << "expected an error";
  } catch (const VulkanError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-gpu-xyz"), std::string::npos) << e.what();
  }
}
