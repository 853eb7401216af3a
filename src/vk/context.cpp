#include "vk/context.h"

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/env.h"
#include "vk/device_select.h"

namespace wb::vk {
namespace {
std::atomic<uint32_t> gProcessValidationErrors{0};
}  // namespace

uint32_t Context::processValidationErrors() {
  return gProcessValidationErrors.load();
}

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  static_cast<Context*>(user)->onValidationMessage(severity, data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

bool layerAvailable(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const auto& l : layers) {
    if (std::strcmp(l.layerName, name) == 0) return true;
  }
  return false;
}

// The feature structures the device is created with, chained in place (not copyable: the pNext chain points
// into the object itself).
struct FeatureChain {
  VkPhysicalDeviceAccelerationStructureFeaturesKHR as{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR rt{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 base{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};

  FeatureChain() {
    rt.pNext = &as;
    f13.pNext = &rt;
    f12.pNext = &f13;
    base.pNext = &f12;
  }
  FeatureChain(const FeatureChain&) = delete;
  FeatureChain& operator=(const FeatureChain&) = delete;
};

// What a device supports of the feature chain (one query).
struct SupportedFeatures : FeatureChain {
  explicit SupportedFeatures(VkPhysicalDevice d) { vkGetPhysicalDeviceFeatures2(d, &base); }

  // The features the workbench cannot run without.
  std::vector<std::string> missingEssentials() const {
    std::vector<std::string> missing;
    auto need = [&](VkBool32 have, const char* name) {
      if (!have) missing.emplace_back(name);
    };
    need(f12.bufferDeviceAddress, "bufferDeviceAddress");
    need(f12.runtimeDescriptorArray, "runtimeDescriptorArray");
    need(f12.descriptorBindingPartiallyBound, "descriptorBindingPartiallyBound");
    need(f12.scalarBlockLayout, "scalarBlockLayout");
    need(f13.dynamicRendering, "dynamicRendering");
    need(f13.synchronization2, "synchronization2");
    need(rt.rayTracingPipeline, "rayTracingPipeline");
    need(as.accelerationStructure, "accelerationStructure");
    return missing;
  }
};

// For device selection: the essential features a candidate lacks. Only devices that could have them at all
// are queried (Vulkan 1.3 and the ray tracing extensions: chaining their feature structures is only valid
// then).
std::vector<std::string> missingDeviceFeatures(VkPhysicalDevice d, const DeviceCandidate& c) {
  if (c.apiVersion < VK_API_VERSION_1_3) return {};
  for (const auto& e : requiredDeviceExtensions()) {
    if (std::find(c.extensions.begin(), c.extensions.end(), e) == c.extensions.end()) return {};
  }
  return SupportedFeatures(d).missingEssentials();
}

// Keeps every shared library loaded now loaded until the process exits. vkDestroyInstance makes the loader
// unload the driver, and the next instance loads it again: NVIDIA's libnvidia-tls takes static TLS each time
// it is loaded, and after ~20 instances in one process (the hard-case suite, a test binary run whole)
// vkCreateInstance fails with "cannot allocate memory in static TLS block" (NVIDIA's driver 580).
// Called before an instance goes, so the driver and what it loaded lazily (ray tracing compiler, layers)
// stay.
void keepLoadedLibrariesResident() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        if (info->dlpi_name && info->dlpi_name[0] == '/')
          static_cast<std::vector<std::string>*>(out)->emplace_back(info->dlpi_name);
        return 0;
      },
      &names);
  // RTLD_NOLOAD: only what is loaded already; RTLD_NODELETE: never unloaded. The handles are kept on purpose.
  for (const auto& n : names) dlopen(n.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}

// The feature chain the device is created with: Vulkan 1.2/1.3 core pieces plus ray tracing, the essentials
// on and the optional ones where `have` supports them.
struct EnabledFeatures : FeatureChain {
  explicit EnabledFeatures(const SupportedFeatures& have) {
    as.accelerationStructure = VK_TRUE;
    rt.rayTracingPipeline = VK_TRUE;
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    f13.maintenance4 = have.f13.maintenance4;
    f12.bufferDeviceAddress = VK_TRUE;
    f12.descriptorIndexing = VK_TRUE;
    f12.runtimeDescriptorArray = VK_TRUE;
    f12.shaderSampledImageArrayNonUniformIndexing = have.f12.shaderSampledImageArrayNonUniformIndexing;
    f12.shaderStorageBufferArrayNonUniformIndexing = have.f12.shaderStorageBufferArrayNonUniformIndexing;
    f12.descriptorBindingPartiallyBound = VK_TRUE;
    f12.descriptorBindingVariableDescriptorCount = have.f12.descriptorBindingVariableDescriptorCount;
    f12.scalarBlockLayout = VK_TRUE;
    f12.hostQueryReset = have.f12.hostQueryReset;
    f12.timelineSemaphore = VK_TRUE;
    base.features.shaderInt64 = have.base.features.shaderInt64;
    base.features.samplerAnisotropy = VK_FALSE;
  }
};

// The first queue family that does graphics and compute.
uint32_t graphicsComputeQueueFamily(VkPhysicalDevice device, const std::string& deviceName) {
  uint32_t n = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &n, families.data());
  for (uint32_t i = 0; i < n; ++i) {
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT))
      return i;
  }
  throw VulkanError("device '" + deviceName + "' has no graphics+compute queue");
}

template <typename T>
void load(VkDevice device, T& fn, const char* name) {
  fn = reinterpret_cast<T>(vkGetDeviceProcAddr(device, name));
  if (!fn) throw VulkanError(std::string("device entry point missing: ") + name);
}

}  // namespace

Context::Context(const ContextOptions& options) {
  try {
    createInstance(options);
    pickDevice(options);
    createDevice(options);
  } catch (...) {
    destroy();
    throw;
  }
}

Context::~Context() {
  destroy();
}

void Context::destroy() {
  if (device_) {
    waitIdle();
    pipelineCache_.reset();  // saves it
    if (fence_) vkDestroyFence(device_, fence_, nullptr);
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) {
    keepLoadedLibrariesResident();
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

void Context::onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const char* message) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return;
  bool error = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  if (error) {
    validationErrors_++;
    gProcessValidationErrors++;
  }
  std::fprintf(stderr, "[vulkan %s] %s\n", error ? "error" : "warning", message);
  std::lock_guard lock(messagesMutex_);
  if (error) messages_.emplace_back(message);
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

void Context::createInstance(const ContextOptions& options) {
  const char* kValidation = "VK_LAYER_KHRONOS_validation";
  bool wantValidation = options.validation || env::enabled("WB_VALIDATION");
  validation_ = wantValidation && layerAvailable(kValidation);
  // Validation that was asked for and cannot run is a failure, never a silent pass.
  if (wantValidation && !validation_)
    throw std::runtime_error(std::string("validation requested (WB_VALIDATION=1) but ") + kValidation +
                             " is not installed (Debian: vulkan-validationlayers)");

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "rt-workbench";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> extensions = options.instanceExtensions;
  std::vector<const char*> layers;
  if (validation_) {
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    layers.push_back(kValidation);
  }
  VkDebugUtilsMessengerCreateInfoEXT dbg{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  dbg.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  dbg.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                    VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  dbg.pfnUserCallback = debugCallback;
  dbg.pUserData = this;

  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  ci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  ci.ppEnabledExtensionNames = extensions.data();
  ci.enabledLayerCount = static_cast<uint32_t>(layers.size());
  ci.ppEnabledLayerNames = layers.data();
  if (validation_) ci.pNext = &dbg;
  WB_VK(vkCreateInstance(&ci, nullptr, &instance_));

  if (validation_) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) WB_VK(create(instance_, &dbg, nullptr, &messenger_));
  }
}

void Context::pickDevice(const ContextOptions& options) {
  uint32_t n = 0;
  WB_VK(vkEnumeratePhysicalDevices(instance_, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  WB_VK(vkEnumeratePhysicalDevices(instance_, &n, devices.data()));

  std::vector<DeviceCandidate> candidates;
  for (auto d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    DeviceCandidate c;
    c.name = p.deviceName;
    c.discrete = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
    c.integrated = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
    c.cpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    c.apiVersion = p.apiVersion;
    uint32_t e = 0;
    vkEnumerateDeviceExtensionProperties(d, nullptr, &e, nullptr);
    std::vector<VkExtensionProperties> exts(e);
    vkEnumerateDeviceExtensionProperties(d, nullptr, &e, exts.data());
    for (const auto& x : exts) c.extensions.emplace_back(x.extensionName);
    c.missingFeatures = missingDeviceFeatures(d, c);
    candidates.push_back(std::move(c));
  }
  auto required = requiredDeviceExtensions();
  if (options.presentation) required.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  DeviceChoice choice = chooseDevice(candidates, required, options.deviceName);
  if (!choice.index) throw VulkanError(choice.error);
  physical_ = devices[*choice.index];
  deviceName_ = candidates[*choice.index].name;
  bool reorderExtension = false;  // the device lists VK_NV_ray_tracing_invocation_reorder
  for (const auto& e : candidates[*choice.index].extensions) {
    if (e == VK_KHR_PIPELINE_LIBRARY_EXTENSION_NAME) pipelineLibrary_ = true;
    if (e == VK_KHR_SHADER_CLOCK_EXTENSION_NAME) shaderClockExtension_ = true;
    if (e == VK_NV_RAY_TRACING_INVOCATION_REORDER_EXTENSION_NAME) reorderExtension = true;
  }
  // The shader clocks, queried only where the extension is (its feature structure is valid only then).
  ShaderClock clocks;
  if (shaderClockExtension_) {
    VkPhysicalDeviceShaderClockFeaturesKHR clock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &clock;
    vkGetPhysicalDeviceFeatures2(physical_, &f2);
    clocks.subgroup = clock.shaderSubgroupClock;
    clocks.device = clock.shaderDeviceClock;
  }
  // Shader execution reordering, queried only where the extension is: the feature, and whether the device
  // reorders at all.
  if (reorderExtension) {
    VkPhysicalDeviceRayTracingInvocationReorderFeaturesNV reorder{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_INVOCATION_REORDER_FEATURES_NV};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f2.pNext = &reorder;
    vkGetPhysicalDeviceFeatures2(physical_, &f2);
    VkPhysicalDeviceRayTracingInvocationReorderPropertiesNV hint{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_INVOCATION_REORDER_PROPERTIES_NV};
    VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    p2.pNext = &hint;
    vkGetPhysicalDeviceProperties2(physical_, &p2);
    if (reorder.rayTracingInvocationReorder)
      invocationReorderSupport_ =
          hint.rayTracingInvocationReorderReorderingHint == VK_RAY_TRACING_INVOCATION_REORDER_MODE_REORDER_NV
              ? "reorders"
              : "no-op";
  }
  // Subgroup operations in ray generation (the measuring variants' lane isolation, DevicePolicy).
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceProperties2 subgroupProps{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  subgroupProps.pNext = &subgroup;
  vkGetPhysicalDeviceProperties2(physical_, &subgroupProps);
  constexpr VkSubgroupFeatureFlags kVote = VK_SUBGROUP_FEATURE_BASIC_BIT | VK_SUBGROUP_FEATURE_VOTE_BIT;
  DeviceTraits traits;
  traits.raygenSubgroupVote = (subgroup.supportedStages & VK_SHADER_STAGE_RAYGEN_BIT_KHR) != 0 &&
                              (subgroup.supportedOperations & kVote) == kVote;
  traits.cpuImplementation = candidates[*choice.index].cpu;
  traits.pipelineLibrarySupported = pipelineLibrary_;
  traits.deferredHostOpsSupported = true;  // VK_KHR_deferred_host_operations is a required extension
  traits.shaderClockSupported = clocks.any();
  traits.invocationReorderSupported = invocationReorderSupport_ != "unsupported";
  traits.invocationReorderReorders = invocationReorderSupport_ == "reorders";
  policy_ = resolveDevicePolicy(traits, PolicyOverrides::fromEnvironment());
  if (policy_.shaderClock) shaderClock_ = clocks;
  if (policy_.deviceClock && shaderClock_.device) shaderClock_.subgroup = false;  // the cost variants read it

  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rtProps{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
  VkPhysicalDeviceAccelerationStructurePropertiesKHR asProps{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  rtProps.pNext = &asProps;
  asProps.pNext = &driver;
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &rtProps;
  vkGetPhysicalDeviceProperties2(physical_, &props);
  rt_.handleSize = rtProps.shaderGroupHandleSize;
  rt_.handleAlignment = rtProps.shaderGroupHandleAlignment;
  rt_.baseAlignment = rtProps.shaderGroupBaseAlignment;
  rt_.maxRecursionDepth = rtProps.maxRayRecursionDepth;
  rt_.maxHitAttributeSize = rtProps.maxRayHitAttributeSize;
  rt_.minScratchAlignment = asProps.minAccelerationStructureScratchOffsetAlignment;
  timestampPeriod_ = props.properties.limits.timestampPeriod;
  driverInfo_ = std::string(driver.driverName) + " " + driver.driverInfo;
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);
}

void Context::createDevice(const ContextOptions& options) {
  queueFamily_ = graphicsComputeQueueFamily(physical_, deviceName_);
  {
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(physical_, &n, families.data());
    timestampValidBits_ = families.at(queueFamily_).timestampValidBits;
  }
  // Selection already refused devices without the essentials; the optional ones are enabled where present.
  const SupportedFeatures have(physical_);
  std::string missing;
  for (const auto& m : have.missingEssentials()) missing += " " + m;
  if (!missing.empty()) throw VulkanError("device '" + deviceName_ + "' lacks features:" + missing);
  const EnabledFeatures features(have);

  std::vector<const char*> extensions;
  for (const auto& e : requiredDeviceExtensions()) extensions.push_back(e.c_str());
  if (pipelineLibrary_) extensions.push_back(VK_KHR_PIPELINE_LIBRARY_EXTENSION_NAME);
  if (options.presentation) extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  // The shader clocks, optional: enabled where the device has them and the policy wants them.
  VkPhysicalDeviceShaderClockFeaturesKHR clock{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_CLOCK_FEATURES_KHR};
  const void* chain = &features.base;
  if (shaderClock_.any()) {
    extensions.push_back(VK_KHR_SHADER_CLOCK_EXTENSION_NAME);
    clock.shaderSubgroupClock = shaderClock_.subgroup;
    clock.shaderDeviceClock = shaderClock_.device;
    clock.pNext = const_cast<void*>(chain);
    chain = &clock;
  }
  // Shader execution reordering, where the policy wants it (the path tracer's WB_INVOCATION_REORDER).
  VkPhysicalDeviceRayTracingInvocationReorderFeaturesNV reorder{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_INVOCATION_REORDER_FEATURES_NV};
  if (policy_.invocationReorder) {
    extensions.push_back(VK_NV_RAY_TRACING_INVOCATION_REORDER_EXTENSION_NAME);
    reorder.rayTracingInvocationReorder = VK_TRUE;
    reorder.pNext = const_cast<void*>(chain);
    chain = &reorder;
  }

  float priority = 1.0f;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = queueFamily_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = chain;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  dci.ppEnabledExtensionNames = extensions.data();
  WB_VK(vkCreateDevice(physical_, &dci, nullptr, &device_));
  vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

  loadDeviceFunctions();
  createPipelineCache(options.pipelineCacheDir);
  createSubmitObjects();
}

void Context::loadDeviceFunctions() {
  load(device_, vkCreateAccelerationStructureKHR, "vkCreateAccelerationStructureKHR");
  load(device_, vkDestroyAccelerationStructureKHR, "vkDestroyAccelerationStructureKHR");
  load(device_, vkGetAccelerationStructureBuildSizesKHR, "vkGetAccelerationStructureBuildSizesKHR");
  load(device_, vkCmdBuildAccelerationStructuresKHR, "vkCmdBuildAccelerationStructuresKHR");
  load(device_, vkGetAccelerationStructureDeviceAddressKHR, "vkGetAccelerationStructureDeviceAddressKHR");
  load(device_, vkCreateRayTracingPipelinesKHR, "vkCreateRayTracingPipelinesKHR");
  load(device_, vkGetRayTracingShaderGroupHandlesKHR, "vkGetRayTracingShaderGroupHandlesKHR");
  load(device_, vkCmdTraceRaysKHR, "vkCmdTraceRaysKHR");
  load(device_, vkCreateDeferredOperationKHR, "vkCreateDeferredOperationKHR");
  load(device_, vkDestroyDeferredOperationKHR, "vkDestroyDeferredOperationKHR");
  load(device_, vkDeferredOperationJoinKHR, "vkDeferredOperationJoinKHR");
  load(device_, vkGetDeferredOperationResultKHR, "vkGetDeferredOperationResultKHR");
  load(device_, vkGetDeferredOperationMaxConcurrencyKHR, "vkGetDeferredOperationMaxConcurrencyKHR");
}

void Context::createPipelineCache(const std::string& dir) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical_, &props);
  std::string cacheFile;
  if (!dir.empty()) {
    char name[64];
    std::snprintf(name, sizeof(name), "vk_pipeline_cache_%04x_%04x.bin", props.vendorID, props.deviceID);
    cacheFile = dir + "/" + name;
  }
  pipelineCache_ = std::make_unique<PipelineCache>(device_, props, cacheFile);
  if (!pipelineCache_->warning().empty())
    std::fprintf(stderr, "warning: %s\n", pipelineCache_->warning().c_str());
}

void Context::createSubmitObjects() {
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT | VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  pci.queueFamilyIndex = queueFamily_;
  WB_VK(vkCreateCommandPool(device_, &pci, nullptr, &pool_));
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  WB_VK(vkCreateFence(device_, &fci, nullptr, &fence_));
}

uint32_t Context::memoryType(uint32_t typeBits, VkMemoryPropertyFlags wanted) const {
  for (uint32_t i = 0; i < memory_.memoryTypeCount; ++i) {
    if ((typeBits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  }
  throw VulkanError("no memory type with the wanted properties");
}

namespace {
std::atomic<bool> gAnyHung{false};
}  // namespace

bool Context::anyHung() {
  return gAnyHung;
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
  submitAndWaitWhile(
      record, [] { return true; }, std::chrono::nanoseconds::max());
}

bool Context::submitAndWaitFor(const std::function<void(VkCommandBuffer)>& record,
                               std::chrono::nanoseconds timeout) {
  return submitAndWaitWhile(
      record, [] { return false; }, timeout);
}

bool Context::submitAndWaitWhile(const std::function<void(VkCommandBuffer)>& record,
                                 const std::function<bool()>& keepWaiting, std::chrono::nanoseconds poll) {
  std::lock_guard lock(submitMutex_);
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  WB_VK(vkAllocateCommandBuffers(device_, &ai, &cmd));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  WB_VK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  WB_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  {
    std::lock_guard qlock(queueMutex_);
    WB_VK(vkQueueSubmit(queue_, 1, &si, fence_));
  }
  const uint64_t ns = poll == std::chrono::nanoseconds::max() ? UINT64_MAX : uint64_t(poll.count());
  VkResult r;
  while ((r = vkWaitForFences(device_, 1, &fence_, VK_TRUE, ns)) == VK_TIMEOUT) {
    if (!keepWaiting()) {
      hung_ = true;
      gAnyHung = true;
      return false;
    }
  }
  WB_VK(r);
  WB_VK(vkResetFences(device_, 1, &fence_));
  vkFreeCommandBuffers(device_, pool_, 1, &cmd);
  return true;
}

void Context::waitIdle() {
  std::lock_guard lock(queueMutex_);
  vkDeviceWaitIdle(device_);
}

}  // namespace wb::vk
