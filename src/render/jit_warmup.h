// Compile-ahead for drivers that compile pipelines lazily. lavapipe's llvmpipe turns a pipeline into machine
// code at its first dispatch, not at vkCreate*Pipelines: the path tracer (every stage inlined into one
// function) takes ~0.8 s to JIT, so the first frame after a hot reload would stall the render loop by that
// much. The warm-up creates the new pipeline on a second VkDevice of the same driver and records a trace of
// zero rays there, which makes llvmpipe compile it (no shader invocation runs, so a stand-in scene and 1x1
// images are enough: the compiled code depends on the SPIR-V, the pipeline layout and the groups' numbers
// (see alignGroupHandles), not on the data bound) and store the result in Mesa's shader disk cache
// (MESA_SHADER_CACHE_DIR). The render device's first trace with its own copy of the pipeline then loads the
// machine code from the cache (~10 ms) instead of compiling it. The hybrid renderer's passes are warmed the
// same way, by a 1x1 frame of a hybrid renderer on the stand-in scene.
//
// Only where the device compiles lazily (Context::cpuDevice()); GPUs compile in vkCreate*Pipelines, which
// already runs off the frame path. WB_JIT_WARMUP=0 turns it off (for measurements), =1 forces it on.
#pragma once
#include <atomic>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <future>
#include <memory>

#include "render/environment.h"
#include "render/gpu_scene.h"
#include "render/hybrid/hybrid_renderer.h"
#include "render/path_tracer.h"
#include "shader/reloader.h"
#include "scene/features.h"
#include "shader/library.h"
#include "vk/context.h"

namespace wb::render {

// Whether pipelines built for `ctx` should be compiled ahead (see above).
bool jitWarmupWanted(const vk::Context& ctx);

// lavapipe numbers ray tracing shader groups per device (a counter in the leading 32-bit word of each group
// handle), and the machine code it compiles for a pipeline contains those numbers: a pipeline warmed on
// another device is the render device's only if its groups got the same numbers. This creates throwaway
// pipelines (general groups of the build's raygen stage) on `ctx` until its lastGroupHandleWord() is `last`.
// False when the device is past `last` already (it cannot count back) or its numbers do not follow. Nothing
// to do for builds without a raygen stage.
bool alignGroupHandles(vk::Context& ctx, const shader::ShaderLibrary::ProgramBuild& build, uint32_t last);

// Bytes of Mesa's shader disk cache (MESA_SHADER_CACHE_DIR; 0 when unset or missing). What a warm-up adds
// there is the compiled pipeline; the tests use it to see who compiled.
uint64_t mesaShaderCacheBytes();

// Hot-reload targets: runs `warm()` on a low-priority thread of its own beside `prepare()` (this device's
// pipeline creation, on the calling thread) and returns what prepare() returned once both are done. A warm-up
// that throws is reported and turns `enabled` off: the first frame with a new pipeline then compiles it, as
// without warm-up.
template <class Prepare, class Warm>
auto prepareBesideWarmup(std::atomic<bool>& enabled, Prepare&& prepare, Warm&& warm) {
  std::future<void> warmed;
  if (enabled) {
    warmed = std::async(std::launch::async, [&] {
      shader::lowerThreadPriority();
      try {
        warm();
      } catch (const std::exception& e) {
        std::fprintf(stderr, "warning: JIT warm-up off after a failure (%s)\n", e.what());
        enabled = false;
      }
    });
  }
  auto result = prepare();
  if (warmed.valid()) warmed.get();
  return result;
}

// The warm-up device and what every warm-up renders with there: a device like `main` (same physical device,
// same validation setting), a shader library with the render side's options (the same SPIR-V cache: first
// builds are cache hits), a stand-in scene (one quad, one material, a sun) and a black environment.
struct WarmupDevice {
  WarmupDevice(const vk::Context& main, const shader::ShaderLibrary::Options& libraryOptions);
  ~WarmupDevice();
  WarmupDevice(const WarmupDevice&) = delete;
  WarmupDevice& operator=(const WarmupDevice&) = delete;

  std::unique_ptr<vk::Context> ctx;
  std::unique_ptr<shader::ShaderLibrary> library;
  scene::Scene scene;
  std::unique_ptr<GpuScene> gpuScene;
  std::unique_ptr<GpuEnvironment> env;
  RenderSettings settings;  // 1x1
};

class PathTracerJitWarmup {
 public:
  // A device like `main` (same physical device, same validation setting), a shader library with
  // `libraryOptions` (the same SPIR-V cache: the stand-in's first build is a cache hit), and a path tracer on
  // a stand-in scene.
  PathTracerJitWarmup(const vk::Context& main, const shader::ShaderLibrary::Options& libraryOptions,
                      const scene::SceneFeatures& features);
  ~PathTracerJitWarmup();
  PathTracerJitWarmup(const PathTracerJitWarmup&) = delete;
  PathTracerJitWarmup& operator=(const PathTracerJitWarmup&) = delete;

  // Creates the pipeline of `build` on the warm-up device and has the driver compile it (blocking; call it
  // off the render thread). `renderDeviceGroupHandle` is the render device's lastGroupHandleWord() from
  // before it created its own pipeline of `build`: the warm-up's groups get the numbers that one's got (see
  // alignGroupHandles). Returns false when that was not possible (this device numbered more groups already:
  // make a new warm-up). Throws what pipeline creation throws.
  bool warm(const shader::ShaderLibrary::ProgramBuild& build, uint32_t renderDeviceGroupHandle);
  // The group handles of the last warmed pipeline: equal to the render device's pipeline's when it matched.
  const std::vector<uint8_t>& groupHandles() const { return tracer_->groupHandles(); }
  uint32_t warmups() const { return warmups_; }

 private:
  WarmupDevice device_;
  std::unique_ptr<PathTracer> tracer_;  // after device_: destroyed first
  uint32_t warmups_ = 0;
};

// The same for the hybrid renderer's passes: a hybrid renderer of the same mode on the stand-in scene, 1x1,
// whose frame runs every pass (the hybrid shaders are not specialised per scene, so they run safely on any
// scene).
class HybridJitWarmup {
 public:
  HybridJitWarmup(const vk::Context& main, const shader::ShaderLibrary::Options& libraryOptions,
                  RenderMode mode, const HybridSettings& hybrid, const std::filesystem::path& shaderRoot);
  ~HybridJitWarmup();
  HybridJitWarmup(const HybridJitWarmup&) = delete;
  HybridJitWarmup& operator=(const HybridJitWarmup&) = delete;

  // Builds `pass` from `build` on the warm-up device and renders one 1x1 frame there. `hybrid` are the render
  // device's current settings (the reflection depth is a specialisation constant of the compiled code);
  // `renderDeviceGroupHandle` and the result as for the path tracer's.
  bool warm(HybridRenderer::Pass pass, const shader::ShaderLibrary::ProgramBuild& build,
            const HybridSettings& hybrid, uint32_t renderDeviceGroupHandle);
  std::vector<uint8_t> groupHandles(HybridRenderer::Pass pass) const { return renderer_->groupHandles(pass); }
  uint32_t warmups() const { return warmups_; }

 private:
  WarmupDevice device_;
  std::unique_ptr<HybridRenderer> renderer_;  // after device_: destroyed first
  uint32_t warmups_ = 0;
};

}  // namespace wb::render
