// Driver-specific policy, in one place: what the workbench does differently per Vulkan driver, resolved once
// per device from what the device is and from the environment's overrides. Nothing else in the code asks
// which driver it runs on; it reads the resolved DevicePolicy (vk::Context::policy()).
//
// A CPU implementation (lavapipe) compiles a pipeline to machine code at its first dispatch, not at
// vkCreate*Pipelines, and shares the CPU with everything else; GPUs compile at creation, off the frame path.
// What follows from that is below; docs/bench/README.md has the measurements behind each choice.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wb::vk {

// What the device is, as far as the policy cares.
struct DeviceTraits {
  bool cpuImplementation = false;  // VK_PHYSICAL_DEVICE_TYPE_CPU
  bool pipelineLibrarySupported = false;
  bool deferredHostOpsSupported = false;
  bool shaderClockSupported = false;  // VK_KHR_shader_clock with the subgroup or the device clock
  bool raygenSubgroupVote = false;    // subgroup basic and vote operations in ray generation shaders
  // VK_NV_ray_tracing_invocation_reorder: the feature, and whether the device says it reorders (its
  // rayTracingInvocationReorderReorderingHint; where it does not, the shader's reorder calls are valid no-ops).
  bool invocationReorderSupported = false;
  bool invocationReorderReorders = false;
};

// The environment's overrides (unset: the default for the device). Each maps to a variable of
// docs/ENVIRONMENT.md.
struct PolicyOverrides {
  std::optional<bool> jitWarmup;            // WB_JIT_WARMUP=0|1
  std::optional<bool> pipelineLibraries;    // WB_PIPELINE_LIBRARY=0|1
  std::optional<bool> deferredHostOps;      // WB_DEFERRED_HOST_OPS=0 (on by default where supported)
  std::optional<bool> cpuShapedShaderCode;  // WB_CPU_DEVICE_CODE=0|1
  std::optional<double> rebuildRestRatio;   // WB_REBUILD_YIELD=R (0 .. 1000)
  std::optional<bool> trialRuns;            // WB_TRIAL_RUN=0|1
  std::optional<double> hangSeconds;        // WB_HANG_SECONDS=S (0.5 .. 3600)
  std::optional<bool> shaderClock;          // WB_SHADER_CLOCK=0 (on by default where supported)
  std::optional<bool> deviceClock;          // WB_DEVICE_CLOCK=1 (the subgroup clock by default)
  std::optional<bool> costIsolation;        // WB_COST_ISOLATE=0|1
  std::optional<bool> splitShadows;         // WB_SPLIT_SHADOWS=0|1
  std::optional<double> splitSlots;         // WB_SPLIT_SLOTS=N (0 .. 18)
  std::optional<bool> invocationReorder;    // WB_INVOCATION_REORDER=0|1
  // Throws std::invalid_argument naming the variable when one holds a value it cannot take.
  static PolicyOverrides fromEnvironment();
};

struct DevicePolicy {
  // Pipelines reach machine code at their first dispatch (the device's first frame with a new pipeline
  // would stall the render loop for the whole compile).
  bool compilesAtFirstDispatch = false;
  // Hot reload has the driver compile a new pipeline ahead, on a second device, before it is installed
  // (render/jit_warmup.h).
  bool jitWarmup = false;
  // Ray tracing pipelines are linked from per-group pipeline libraries, so an edit recompiles one group.
  // Off on lavapipe: Mesa 25.0 links them without an error but the linked pipeline renders nothing.
  bool pipelineLibraries = false;
  // Monolithic ray tracing pipelines are created through a deferred host operation on several threads.
  // Never on lavapipe: its Mesa 25.0 crashes linking inside a deferred operation, and it compiles later
  // anyway.
  bool deferredHostOps = false;
  // The path tracer's shaders are shaped for a JIT that compiles every inlined copy of a function
  // (WB_CPU_DEVICE=1, shaders/pathtracer/common.glsl); GPUs keep the straight-line code.
  bool cpuShapedShaderCode = false;
  // While a rebuild compiles, render loops rest this many frame times after each frame so the compile gets
  // the cores (0: never rest). `watch` keeps a tenth of the CPU for its frames, the window a quarter (it
  // still answers input at that share).
  double watchRestRatio = 0.0;
  double windowRestRatio = 0.0;
  // ... and the window traces with this share of its per-frame budget meanwhile.
  double windowTraceShareWhileCompiling = 1.0;
  // Every new pipeline of a hot reload first renders a small frame on a second device (the warm-up's),
  // where a shader that never returns hangs nothing that matters: the reload is refused and the last good
  // pipeline stays. On every device: no driver here can cancel a running shader.
  bool trialRuns = true;
  // A frame that has not finished after this long, and after many times the frames before it, counts as
  // hung (the trial frame's, and the render loop's watchdog).
  double hangSeconds = 5.0;
  // The device's work runs on the CPU, on threads the driver starts with the device: the trial frame (and the
  // compile ahead) of a hot reload counts as hung only once those threads have also spent its limit in CPU
  // time. A shader in an endless loop spends it at the wall clock's pace; a warm-up starved by other work on
  // the machine (it runs at a lowered priority) does not, and is waited for (up to 20 times the limit:
  // live/jit_warmup.h, warmupFrameMayStillFinish).
  bool hangCountsDriverCpu = false;
  // VK_KHR_shader_clock is enabled, for the path tracer's cost variants (the cost heat maps, the inspector's
  // per-vertex cost): wherever the device has it, unless WB_SHADER_CLOCK=0 (a device without one, for
  // testing, or a driver whose clock misbehaves).
  bool shaderClock = false;
  // The cost variants read the device clock (shaderDeviceClock) where the device has both it and the subgroup
  // clock, which they read by default: WB_DEVICE_CLOCK=1, to compare the two where the subgroup clock counts
  // more than the invocation's own work (an SM's cycles spent on other warps).
  bool deviceClock = false;
  // The cost variant traces each sample alone in its subgroup (shaders/pathtracer/raygen.rgen), so that a
  // pixel's clocks are its own path's work and not its subgroup's slowest lane's, on devices whose ray
  // generation has subgroup operations (GPUs; not lavapipe, whose lanes stay shared). It then runs at a
  // fraction of the device's width (the H100: 8.6-9.9x the default variant's time at 1920x1080,
  // docs/cost.md). WB_COST_ISOLATE=0: the subgroup's time per pixel, what the device pays for divergence.
  bool costIsolatesLanes = false;
  // The cost views and maps read each pixel's running median of a sample's clocks rather than its mean: on a
  // CPU device the clock runs on while the OS runs another thread, and the few invocations it preempted would
  // set the means (lavapipe on a busy machine: a preempted group of pixels at 100x the others).
  bool costByMedian = false;
  // The path tracer traces next-event estimation's shadow rays in a launch of their own after the path rays'
  // (shaders/pathtracer/shadow_split.rgen) where its variant allows (PathTracer::splitsShadows): on GPUs,
  // where it takes 6-13% off a sample (docs/bench/roofline.md, an H100); not on lavapipe, where the second
  // pipeline costs a JIT compile and the sample is no faster. WB_SPLIT_SHADOWS=0|1.
  bool splitShadows = false;
  // The most shadow requests a sample leaves for the shadow launch (fewer where the memory budget says so;
  // the rest are traced in the path loop). WB_SPLIT_SLOTS=N lowers it (0: every shadow ray in the path loop).
  uint32_t splitSlotsLimit = 18;
  // Shader execution reordering (VK_NV_ray_tracing_invocation_reorder) in the path tracer's path rays
  // (shaders/pathtracer/raygen.rgen, WB_INVOCATION_REORDER): where the device has the feature and says it
  // reorders; WB_INVOCATION_REORDER=1 also where it has the feature but says it does not (to measure the
  // calls' cost), =0 never.
  bool invocationReorder = false;
};

DevicePolicy resolveDevicePolicy(const DeviceTraits& device, const PolicyOverrides& overrides);

// Environment variables the workbench sets for the Vulkan drivers unless the user set them (an empty value
// counts as unset). Drivers read them once, when they load, so this must run before the process's first
// Vulkan instance: the commands and RenderSession call it (the first call decides, later ones return what it
// did).
//
// - LP_NATIVE_VECTOR_WIDTH=128: llvmpipe (lavapipe) compiles shaders 4 lanes wide instead of its 8-lane AVX2
//   default: the path tracer's pipeline JITs in much less time while the trace rate and every image stay the
//   same, at some cost to the window's raster work (docs/bench/lavapipe_vector_width.md). GPU drivers ignore
//   it. Left alone when the user set a MESA_SHADER_CACHE_DIR of their own (see below).
// - MESA_SHADER_CACHE_DIR=<cacheDir>/mesa/lp<width> (the user's width or ours): Mesa's shader disk cache
// under
//   the workbench's shader cache, one folder per width, because llvmpipe's cache key leaves the width out and
//   code compiled at another width corrupts memory when loaded.
// Returns "NAME=value" for each variable it set. Throws as checkDriverEnvironment() does.
std::vector<std::string> applyDriverDefaults(const std::filesystem::path& cacheDir);

// The variables of the drivers that the user may set and a driver would crash on: LP_NATIVE_VECTOR_WIDTH is
// 128, 256 or 512 (llvmpipe takes any number and crashes compiling at 64, 384, 1024 or 0). Throws
// std::invalid_argument naming the variable and what it takes.
void checkDriverEnvironment();

}  // namespace wb::vk
