// Vulkan result checking: every failing call becomes an exception naming the call and the result.
#pragma once
#include <stdexcept>
#include <string>
#include <vulkan/vulkan.h>

namespace wb::vk {

struct VulkanError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const char* resultName(VkResult r);
[[noreturn]] void throwVkError(VkResult r, const char* what, const char* file, int line);

}  // namespace wb::vk

#define WB_VK(call)                                                                    \
  do {                                                                                 \
    VkResult wb_r_ = (call);                                                           \
    if (wb_r_ != VK_SUCCESS) ::wb::vk::throwVkError(wb_r_, #call, __FILE__, __LINE__); \
  } while (0)
