// The second device a hot reload's new pipelines pass through before they are installed:
// - Compile-ahead for drivers that compile pipelines lazily (DevicePolicy::jitWarmup). lavapipe's llvmpipe
//   turns a pipeline into machine code at its first dispatch, not at vkCreate*Pipelines: the path tracer
//   (every stage inlined into one function) would stall the render loop for the whole JIT at its first frame
//   after a hot reload. The warm-up builds the new pipeline in a renderer like the edited one
//   (render::Renderer::makeLike) on a stand-in scene and records a sample with as little work as it allows,
//   which makes llvmpipe compile it and store the result in Mesa's shader disk cache (MESA_SHADER_CACHE_DIR).
//   The render device's first frame with its own copy of the pipeline then loads the machine code from the
//   cache instead of compiling it. The compiled code depends on the SPIR-V, the pipeline layout, the
//   specialisation constants and the groups' numbers (see alignGroupCounter), not on the data bound.
// - A trial frame on every device, unless DevicePolicy::trialRuns is off: a small image of real paths on the
//   stand-in, with a time limit. A shader that never returns hangs this device, which nothing else uses,
//   instead of the render device: the reload is refused (TrialHang) and the last good pipeline draws on.
// HotReload runs it beside the render device's own pipeline creation.
#pragma once
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "render/renderer.h"
#include "shader/library.h"
#include "live/reloader.h"
#include "live/warmup_slot.h"
#include "vk/context.h"

namespace wb::live {

// lavapipe numbers ray tracing shader groups per device (a counter in the leading 32-bit word of each group
// handle), and the machine code it compiles for a pipeline contains those numbers: a pipeline warmed on
// another device is the render device's only if its groups got the same numbers.
//
// probeGroupCounter creates a throwaway pipeline of one group (the build's raygen stage) on `ctx` and returns
// its group's number: the next pipeline's groups follow it. nullopt for builds without a raygen stage.
std::optional<uint32_t> probeGroupCounter(vk::Context& ctx, const shader::ShaderLibrary::ProgramBuild& build);
// Brings `ctx`'s counter to `last` with throwaway pipelines, so that its next pipeline's groups get the
// numbers of a pipeline made on a device whose probe returned `last`. False when `ctx` is past `last` already
// (it cannot count back) or its numbers do not follow. True (nothing to do) for builds without a raygen
// stage.
bool alignGroupCounter(vk::Context& ctx, const shader::ShaderLibrary::ProgramBuild& build, uint32_t last);

// Bytes of Mesa's shader disk cache (MESA_SHADER_CACHE_DIR; 0 when unset or missing). What a warm-up adds
// there is the compiled pipeline; the tests use it to see who compiled.
uint64_t mesaShaderCacheBytes();

// Whether a warm-up frame that has run for `wall` seconds, while its device's driver threads spent `cpu`
// seconds of CPU time, is still waited for under a limit of `limit` seconds. Past the limit it is not, unless
// `countCpu` (DevicePolicy::hangCountsDriverCpu) and the threads have spent less than the limit: then the
// machine's other work starves the frame, and it is waited for up to 20 limits.
bool warmupFrameMayStillFinish(double wall, double cpu, double limit, bool countCpu);

// The warm-up device and what every warm-up renders with there: a device like `main` (same physical device,
// same validation setting), a shader library with the render side's options (the same SPIR-V cache: first
// builds are cache hits), a stand-in scene (one quad, one material, a sun) and a black environment.
struct WarmupDevice {
  WarmupDevice(const vk::Context& main, const shader::ShaderLibrary::Options& libraryOptions);
  ~WarmupDevice();
  WarmupDevice(const WarmupDevice&) = delete;
  WarmupDevice& operator=(const WarmupDevice&) = delete;
  render::RendererResources resources() const;

  std::unique_ptr<vk::Context> ctx;
  // The threads started while this was made (the driver's, for this device: where a CPU driver runs its
  // work).
  std::vector<long> driverThreads;
  std::unique_ptr<shader::ShaderLibrary> library;
  scene::Scene scene;
  std::unique_ptr<render::GpuScene> gpuScene;
  std::unique_ptr<render::GpuEnvironment> env;
};

// The side the trial frame renders: every pixel traces (16x16 pixels, the stand-in's quad and sky).
inline constexpr uint32_t kTrialSize = 16;

class JitWarmup {
 public:
  // A warm-up device and, on it, a renderer like `like` at kTrialSize on the stand-in scene.
  JitWarmup(const render::Renderer& like, const shader::ShaderLibrary::Options& libraryOptions);
  ~JitWarmup();
  JitWarmup(const JitWarmup&) = delete;
  JitWarmup& operator=(const JitWarmup&) = delete;

  // Builds the pipeline of `like`'s pass number `passIndex` (in passes() order) from `build` on the warm-up
  // device, and there (blocking; call it off the render thread):
  // - with `compileAhead`: records a sample with as little work as the renderer allows, so that a driver
  //   that compiles at the first dispatch compiles it into its disk cache. `renderDeviceGroupCounter` is
  //   probeGroupCounter() of the render device, taken before it built its own pipeline of `build`;
  // - renders a trial frame of kTrialSize pixels, waiting at most hangSeconds() for it: a shader that never
  //   returns hangs this device, not the render device (the reload is refused).
  // Throws what pipeline creation throws.
  WarmOutcome warm(const render::Renderer& like, size_t passIndex,
                   const shader::ShaderLibrary::ProgramBuild& build,
                   std::optional<uint32_t> renderDeviceGroupCounter, bool compileAhead);
  // How long the last trial frame was given (s), and whether a frame of this warm-up never finished.
  double trialLimitSeconds() const { return trialLimit_; }
  // The CPU seconds the device's driver threads spent during the last frame that hung (where the policy
  // counts them: DevicePolicy::hangCountsDriverCpu; else a negative value).
  double hangCpuSeconds() const { return hangCpuSeconds_; }
  bool hung() const { return device_.ctx->hung(); }
  // The group handles of the last warmed pipeline (empty when it was not a ray tracing pipeline): equal to
  // the render device's pipeline's when their numbers matched.
  const std::vector<uint8_t>& groupHandles() const { return handles_; }
  uint32_t warmups() const { return warmups_; }

 private:
  WarmupDevice device_;
  std::unique_ptr<render::Renderer> renderer_;  // after device_: destroyed first
  std::vector<uint8_t> handles_;
  uint32_t warmups_ = 0;
  std::vector<double> trialSeconds_;    // the finished trial frames', for the limit of the next
  std::vector<double> compileSeconds_;  // the finished compiles ahead', for the limit of the next
  double trialLimit_ = 0;
  double hangCpuSeconds_ = -1;

  // Submits `record` on the warm-up device and waits: false once the frame counts as hung
  // (warmupFrameMayStillFinish).
  bool finishes(const std::function<void(VkCommandBuffer)>& record, double limit, bool countCpu);
};

// A reload's new pipeline whose trial frame did not finish (JitWarmup::warm): what the user reads.
struct TrialHang : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Runs `warm()` on a low-priority thread of its own beside `build()` (the render device's pipeline creation,
// on the calling thread) and returns what build() returned once both are done. A warm-up that throws (the
// program's pipeline cannot be built: build() throws the same) is reported and sets `failed`: that
// pipeline's first frame compiles it, as without warm-up; the next reload warms again.
template <class Build, class Warm>
auto buildBesideWarmup(Build&& build, Warm&& warm, bool& failed) {
  failed = false;
  std::future<void> warmed = std::async(std::launch::async, [&] {
    lowerThreadPriority();
    try {
      warm();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "warning: JIT warm-up failed for this reload (%s)\n", e.what());
      failed = true;
    }
  });
  // The warm-up thread reads what build() may throw over: it finishes before this returns or throws.
  struct Join {
    std::future<void>& f;
    ~Join() {
      if (f.valid()) f.wait();
    }
  } join{warmed};
  return build();
}

}  // namespace wb::live
