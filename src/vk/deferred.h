// Pipeline creation through VK_KHR_deferred_host_operations: the driver may split one
// vkCreateRayTracingPipelinesKHR into work that several threads join (NVIDIA compiles the stages of one call
// in parallel that way); drivers that do not defer just run the call. Not on CPU devices (lavapipe: see
// runDeferred). WB_DEFERRED_HOST_OPS=0 turns it off (for measurements).
#pragma once
#include <functional>
#include <vulkan/vulkan.h>

#include "vk/context.h"

namespace wb::vk {

// Whether pipeline creation goes through deferred operations (the extension is always enabled: ray tracing
// requires it); WB_DEFERRED_HOST_OPS=0 says no.
bool deferredHostOpsWanted();

// Calls `call` with a deferred operation (or VK_NULL_HANDLE when turned off), joins it from up to
// `maxThreads` threads (the calling one included; 0 = all cores but one) when the driver deferred it, and
// returns the call's result: VK_SUCCESS, or the error code the call or the operation ended with.
VkResult runDeferred(const Context& ctx, const std::function<VkResult(VkDeferredOperationKHR)>& call,
                     unsigned maxThreads = 0);

}  // namespace wb::vk
