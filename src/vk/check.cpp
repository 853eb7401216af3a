#include "vk/check.h"

namespace wb::vk {

const char* resultName(VkResult r) {
  switch (r) {
#define WB_CASE(x) \
  case x:          \
    return #x;
    WB_CASE(VK_SUCCESS)
    WB_CASE(VK_NOT_READY)
    WB_CASE(VK_TIMEOUT)
    WB_CASE(VK_INCOMPLETE)
    WB_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    WB_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    WB_CASE(VK_ERROR_INITIALIZATION_FAILED)
    WB_CASE(VK_ERROR_DEVICE_LOST)
    WB_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    WB_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    WB_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    WB_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    WB_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    WB_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    WB_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    WB_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    WB_CASE(VK_SUBOPTIMAL_KHR)
    WB_CASE(VK_ERROR_SURFACE_LOST_KHR)
    WB_CASE(VK_OPERATION_DEFERRED_KHR)
    WB_CASE(VK_OPERATION_NOT_DEFERRED_KHR)
#undef WB_CASE
    default:
      return "VK_ERROR_UNKNOWN";
  }
}

void throwVkError(VkResult r, const char* what, const char* file, int line) {
  throw VulkanError(std::string(what) + " failed with " + resultName(r) + " (" + file + ":" +
                    std::to_string(line) + ")");
}

}  // namespace wb::vk
