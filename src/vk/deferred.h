// Pipeline creation through VK_KHR_deferred_host_operations: the driver may split one
// vkCreateRayTracingPipelinesKHR into work that several threads join (NVIDIA compiles the stages of one call
// in parallel that way); drivers that do not defer just run the call. Only where the device's policy says so
// (DevicePolicy::deferredHostOps).
#pragma once
#include <functional>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::vk {

// Calls `call` with a deferred operation (or VK_NULL_HANDLE where the policy says no), joins it from up to
// `maxThreads` threads (the calling one included; 0 = all cores but one) when the driver deferred it, and
// returns the call's result: VK_SUCCESS, or the error code the call or the operation ended with.
VkResult runDeferred(const Context& ctx, const std::function<VkResult(VkDeferredOperationKHR)>& call,
                     unsigned maxThreads = 0);

}  // namespace wb::vk
