#include "vk/deferred.h"

#include <algorithm>
#include <thread>
#include <vector>

namespace wb::vk {

VkResult runDeferred(const Context& ctx, const std::function<VkResult(VkDeferredOperationKHR)>& call,
                     unsigned maxThreads) {
  if (!ctx.policy().deferredHostOps || !ctx.vkCreateDeferredOperationKHR) return call(VK_NULL_HANDLE);
  VkDeferredOperationKHR op = VK_NULL_HANDLE;
  if (ctx.vkCreateDeferredOperationKHR(ctx.device(), nullptr, &op) != VK_SUCCESS) return call(VK_NULL_HANDLE);
  VkResult result = call(op);
  if (result == VK_OPERATION_NOT_DEFERRED_KHR) {
    result = VK_SUCCESS;  // done already
  } else if (result == VK_OPERATION_DEFERRED_KHR) {
    // Every joining thread loops until the operation is complete or has no more work for it.
    auto join = [&] {
      for (;;) {
        const VkResult r = ctx.vkDeferredOperationJoinKHR(ctx.device(), op);
        if (r == VK_THREAD_IDLE_KHR) {
          std::this_thread::yield();
          continue;
        }
        return;  // VK_SUCCESS (complete), VK_THREAD_DONE_KHR (nothing left for this thread) or an error
      }
    };
    // By default one core stays free for the render loop (a hot reload builds while frames are drawn).
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const unsigned limit = maxThreads ? maxThreads : std::max(1u, cores - 1);
    const unsigned wanted = std::min(limit, ctx.vkGetDeferredOperationMaxConcurrencyKHR(ctx.device(), op));
    std::vector<std::thread> helpers;
    for (unsigned i = 1; i < wanted; ++i) helpers.emplace_back(join);
    join();
    for (auto& t : helpers) t.join();
    // Threads that got VK_THREAD_DONE_KHR may return before the last one finishes: wait for the result.
    while ((result = ctx.vkGetDeferredOperationResultKHR(ctx.device(), op)) == VK_NOT_READY)
      std::this_thread::yield();
  }
  ctx.vkDestroyDeferredOperationKHR(ctx.device(), op, nullptr);
  return result;
}

}  // namespace wb::vk
