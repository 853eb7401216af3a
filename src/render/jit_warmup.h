// Compile-ahead for drivers that compile pipelines lazily. lavapipe's llvmpipe turns a pipeline into machine
// code at its first dispatch, not at vkCreate*Pipelines: the path tracer (every stage inlined into one
// function) takes ~0.8 s to JIT, so the first frame after a hot reload would stall the render loop by that
// much. The warm-up creates the new pipeline on a second VkDevice of the same driver and records a trace of
// zero rays there, which makes llvmpipe compile it (no shader invocation runs, so a stand-in scene and 1x1
// images are enough: the compiled code depends on the SPIR-V and the pipeline layout, not on the data bound)
// and store the result in Mesa's shader disk cache (MESA_SHADER_CACHE_DIR). The render device's first trace
// with its own copy of the pipeline then loads the machine code from the cache (~10 ms) instead of compiling
// it.
//
// Only where the device compiles lazily (Context::cpuDevice()); GPUs compile in vkCreate*Pipelines, which
// already runs off the frame path. WB_JIT_WARMUP=0 turns it off (for measurements), =1 forces it on.
#pragma once
#include <memory>

#include "render/environment.h"
#include "render/gpu_scene.h"
#include "render/path_tracer.h"
#include "scene/features.h"
#include "shader/library.h"
#include "vk/context.h"

namespace wb::render {

// Whether pipelines built for `ctx` should be compiled ahead (see above).
bool jitWarmupWanted(const vk::Context& ctx);

// Bytes of Mesa's shader disk cache (MESA_SHADER_CACHE_DIR; 0 when unset or missing). What a warm-up adds
// there is the compiled pipeline; the tests use it to see who compiled.
uint64_t mesaShaderCacheBytes();

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
  // off the render thread). Returns the milliseconds it took. Throws what pipeline creation throws.
  double warm(const shader::ShaderLibrary::ProgramBuild& build);
  uint32_t warmups() const { return warmups_; }
  const vk::Context& context() const { return *ctx_; }

 private:
  std::unique_ptr<vk::Context> ctx_;
  std::unique_ptr<shader::ShaderLibrary> library_;
  scene::Scene scene_;
  std::unique_ptr<GpuScene> gpuScene_;
  std::unique_ptr<GpuEnvironment> env_;
  std::unique_ptr<PathTracer> tracer_;
  uint32_t warmups_ = 0;
};

}  // namespace wb::render
