// The Vulkan instance, the chosen device with ray tracing enabled, one queue, and one-shot command helpers.
#pragma once
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

#include "vk/check.h"
#include "vk/driver_policy.h"
#include "vk/pipeline_cache.h"

namespace wb::vk {

struct ContextOptions {
  std::string deviceName;   // --device override (substring match)
  bool validation = false;  // Khronos validation layer, if installed (also on with WB_VALIDATION=1)
  std::vector<const char*> instanceExtensions;  // e.g. from glfwGetRequiredInstanceExtensions
  bool presentation = false;                    // enable VK_KHR_swapchain on the device
  std::string
      pipelineCacheDir;  // where the VkPipelineCache persists (a file per device); empty = memory only
};

// The shader clocks of VK_KHR_shader_clock the device was created with (none unless
// DevicePolicy::shaderClock).
struct ShaderClock {
  bool subgroup = false;  // shaderSubgroupClock (GLSL clockARB: on GPUs the multiprocessor's cycle counter)
  bool device = false;    // shaderDeviceClock (GLSL clockRealtimeEXT)
  bool any() const { return subgroup || device; }
};

struct RayTracingProperties {
  uint32_t handleSize = 0;
  uint32_t handleAlignment = 0;
  uint32_t baseAlignment = 0;
  uint32_t maxRecursionDepth = 0;
  uint32_t minScratchAlignment = 0;
  uint32_t maxHitAttributeSize = 32;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  const std::string& deviceName() const { return deviceName_; }
  const std::string& driverInfo() const { return driverInfo_; }
  const RayTracingProperties& rayTracing() const { return rt_; }
  bool validationEnabled() const { return validation_; }
  bool pipelineLibrarySupported() const { return pipelineLibrary_; }
  // What this device needs done differently (vk/driver_policy.h), resolved when the device is made.
  const DevicePolicy& policy() const { return policy_; }
  float timestampPeriodNs() const { return timestampPeriod_; }
  // Bits of a timestamp the queue writes (0: the queue has no timestamps).
  uint32_t timestampValidBits() const { return timestampValidBits_; }
  const ShaderClock& shaderClock() const { return shaderClock_; }
  // VK_NV_ray_tracing_invocation_reorder on this device: "reorders", "no-op" (the feature, but the device
  // says it does not reorder) or "unsupported"; whether the path tracer uses it is
  // policy().invocationReorder.
  const std::string& invocationReorderSupport() const { return invocationReorderSupport_; }
  // The pipeline cache every pipeline is created with (persisted at exit when a directory was given).
  VkPipelineCache pipelineCache() const { return pipelineCache_ ? pipelineCache_->handle() : VK_NULL_HANDLE; }
  PipelineCache* pipelineCacheObject() { return pipelineCache_.get(); }

  // Validation messages of severity error seen so far (tests assert zero).
  uint32_t validationErrors() const { return validationErrors_.load(); }
  // Validation errors of every Context of this process so far (the workbench's exit status reports them).
  static uint32_t processValidationErrors();
  std::vector<std::string> validationMessages() const;

  uint32_t memoryType(uint32_t typeBits, VkMemoryPropertyFlags wanted) const;

  // Records with `record` into a fresh command buffer, submits and waits.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record);
  // The same, waiting at most `timeout`: false when the work has not finished by then. The device is then
  // busy for good as far as this process knows (no driver here cancels a running shader): the context is
  // marked hung and must not be used or destroyed (hung(); leak it).
  bool submitAndWaitFor(const std::function<void(VkCommandBuffer)>& record, std::chrono::nanoseconds timeout);
  // The same, waiting while keepWaiting() says to (asked every `poll` until the work has finished): false,
  // and the context hung as above, once it says not to.
  bool submitAndWaitWhile(const std::function<void(VkCommandBuffer)>& record,
                          const std::function<bool()>& keepWaiting,
                          std::chrono::nanoseconds poll = std::chrono::milliseconds(100));
  bool hung() const { return hung_; }
  // Whether any context of the process hung: its threads may never end, so the process ends with _exit
  // rather than running the drivers' exit handlers (app/main.cpp).
  static bool anyHung();
  // The queue is shared by the render loop and background work: hold this while submitting.
  std::mutex& queueMutex() { return queueMutex_; }
  // vkDeviceWaitIdle under the queue's lock (it accesses every queue of the device, which a submission on
  // another thread must not meet); never call it while holding queueMutex().
  void waitIdle();

  // Extension entry points.
  PFN_vkCreateAccelerationStructureKHR vkCreateAccelerationStructureKHR = nullptr;
  PFN_vkDestroyAccelerationStructureKHR vkDestroyAccelerationStructureKHR = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR vkGetAccelerationStructureBuildSizesKHR = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR vkCmdBuildAccelerationStructuresKHR = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR vkGetAccelerationStructureDeviceAddressKHR = nullptr;
  PFN_vkCreateRayTracingPipelinesKHR vkCreateRayTracingPipelinesKHR = nullptr;
  PFN_vkGetRayTracingShaderGroupHandlesKHR vkGetRayTracingShaderGroupHandlesKHR = nullptr;
  PFN_vkCmdTraceRaysKHR vkCmdTraceRaysKHR = nullptr;
  PFN_vkCreateDeferredOperationKHR vkCreateDeferredOperationKHR = nullptr;
  PFN_vkDestroyDeferredOperationKHR vkDestroyDeferredOperationKHR = nullptr;
  PFN_vkDeferredOperationJoinKHR vkDeferredOperationJoinKHR = nullptr;
  PFN_vkGetDeferredOperationResultKHR vkGetDeferredOperationResultKHR = nullptr;
  PFN_vkGetDeferredOperationMaxConcurrencyKHR vkGetDeferredOperationMaxConcurrencyKHR = nullptr;

  // Called from the debug messenger.
  void onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const char* message);

 private:
  void createInstance(const ContextOptions& options);
  void pickDevice(const ContextOptions& options);
  void createDevice(const ContextOptions& options);
  void loadDeviceFunctions();  // the extension entry points above
  // The pipeline cache, persisted in `dir` (a file per device) unless it is empty.
  void createPipelineCache(const std::string& dir);
  void createSubmitObjects();  // submitAndWait's command pool and fence
  void destroy();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::string deviceName_;
  std::string driverInfo_;
  RayTracingProperties rt_;
  VkPhysicalDeviceMemoryProperties memory_{};
  bool validation_ = false;
  bool pipelineLibrary_ = false;
  DevicePolicy policy_;
  float timestampPeriod_ = 1.0f;
  uint32_t timestampValidBits_ = 0;
  ShaderClock shaderClock_;
  bool shaderClockExtension_ = false;  // the device lists VK_KHR_shader_clock
  std::string invocationReorderSupport_ = "unsupported";
  std::atomic<uint32_t> validationErrors_{0};
  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
  std::mutex queueMutex_;
  std::mutex submitMutex_;
  std::atomic<bool> hung_{false};
  std::unique_ptr<PipelineCache> pipelineCache_;
};

}  // namespace wb::vk
