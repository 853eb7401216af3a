// The progressive path tracer pass: the ray tracing pipeline (raygen path loop, closest-hit shading, any-hit
// alpha, environment and shadow miss), its accumulation and AOV images, and hot-swappable pipelines.
#pragma once
#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "render/environment.h"
#include "render/gpu_scene.h"
#include "render/hot_reload.h"
#include "render/settings.h"
#include "render/warmup_slot.h"
#include "scene/features.h"
#include "scene/scene.h"
#include "shader/library.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

namespace wb::render {

class PathTracerJitWarmup;

struct CameraState {
  glm::mat4 view{1.0f};  // world to camera
  float yfov = 0.7f;
  float znear = 0.01f;
};
CameraState cameraFromScene(const scene::Camera& camera);

// The AOV images the path tracer keeps when settings.aov is on (see gpu_types.h for their channels).
enum class Aov { Albedo, Normal, Info };

struct PixelRegion {
  uint32_t x = 0, y = 0, width = 0, height = 0;
};

// A pipeline built (off the frame path) and waiting to replace the running one at a frame boundary.
struct PreparedPipeline {
  std::unique_ptr<vk::PipelineLayout> layout;
  std::unique_ptr<vk::RayTracingPipeline> pipeline;
};

class PathTracer {
 public:
  PathTracer(vk::Context& ctx, shader::ShaderLibrary& library, const GpuScene& scene,
             const GpuEnvironment& env, const RenderSettings& settings,
             const scene::SceneFeatures& features = scene::genericFeatures());
  ~PathTracer();

  // Shader stages of the path tracer for a feature set: no any-hit stage when every material is opaque.
  // cpuDeviceCode defines WB_CPU_DEVICE=1: code shaped for a driver that JIT-compiles every inlined copy of a
  // function at the first trace (shaders/pathtracer/common.glsl).
  static std::vector<shader::ShaderKey> stageKeys(const scene::SceneFeatures& features, bool cpuDeviceCode);
  // Whether this tracer's shaders are shaped for a CPU device: on lavapipe; WB_CPU_DEVICE_CODE=0/1 forces it.
  bool cpuDeviceCode() const { return cpuDeviceCode_; }
  shader::ShaderLibrary::ProgramId program() const { return program_; }
  const scene::SceneFeatures& features() const { return features_; }
  // Switches to the variant for `features` (registering it once; compiled variants come from the cache) and
  // rebuilds the pipeline. Returns true when the program changed (hot-reload targets follow program()).
  bool setFeatures(const scene::SceneFeatures& features);

  void setCamera(const CameraState& camera);
  void setSettings(
      const RenderSettings& settings);  // resizes images when the size changed; resets accumulation
  const RenderSettings& settings() const { return settings_; }
  // Points the tracer at another environment (the window's environment choice); waits for the device, resets
  // accumulation. `env` must outlive the tracer or the next setEnvironment.
  void setEnvironment(const GpuEnvironment& env);
  void resetAccumulation() { sampleIndex_ = 0; }

  // Records one sample for `region` (whole image when empty) into cmd. Call advanceSample() once every region
  // of the image got this sample.
  void record(VkCommandBuffer cmd, std::optional<PixelRegion> region = std::nullopt);
  void advanceSample() { ++sampleIndex_; }
  // Convenience: traces `samples` full-image samples, submitting and waiting for each.
  void render(uint32_t samples);
  uint32_t samplesAccumulated() const { return sampleIndex_; }

  // Hot reload in two steps: prepare (any thread; creates the layout and pipeline) and commit (render thread,
  // at a frame boundary; resets accumulation). The old pipeline keeps rendering until the commit.
  std::unique_ptr<PreparedPipeline> preparePipeline(const shader::ShaderLibrary::ProgramBuild& build) const;
  void commitPipeline(std::unique_ptr<PreparedPipeline> prepared);
  void swapPipeline(const shader::ShaderLibrary::ProgramBuild& build);  // both at once
  // Registers the current program with a HotReload ("pathtracer"): prepare on its worker, commit at poll().
  void addHotReloadTarget(HotReload& hot);
  double lastPipelineMs() const { return pipelineMs_; }
  // Hot reloads on a lazily compiling driver (lavapipe) also have the driver compile the new pipeline on a
  // second device before the commit, so the first frame with it does not stall (render/jit_warmup.h).
  bool jitWarmupEnabled() const { return warmupEnabled_; }
  // The warm-up device is made ahead, when a hot reload target is added: true once it exists or is being
  // made.
  bool jitWarmupPresent() const { return warmup_.present(); }
  uint32_t jitWarmups() const;
  // Warm-ups whose pipeline came out different from this device's (other group handles): wasted, the first
  // frame compiled after all.
  uint32_t jitWarmupMismatches() const { return warmupMismatches_; }
  // On GPUs with VK_KHR_pipeline_library (not lavapipe; WB_PIPELINE_LIBRARY=0/1 forces it) pipelines are
  // linked from per-group libraries: an edit recompiles only the changed group. nullptr when monolithic.
  const vk::RtLibraryCache* libraryCache() const { return libraries_.get(); }
  bool pipelineLinked() const { return pipeline_ && pipeline_->linked(); }
  const std::vector<uint8_t>& groupHandles() const { return pipeline_->sbt().groupHandles(); }

  // Readbacks (they wait for the device).
  std::vector<float> readAccumulation() const;  // RGBA32F, alpha = samples accumulated in the pixel
  std::vector<float> readAov(Aov aov) const;    // RGBA, from the half-float AOV images
  const vk::Image& aovImage(Aov aov) const {
    return aov == Aov::Albedo ? albedo_ : aov == Aov::Normal ? normal_ : info_;
  }
  gpu::Counters readCounters() const;
  void resetCounters();

  const vk::Image& accumulationImage() const { return accum_; }
  const vk::PipelineLayout& layout() const { return *layout_; }

 private:
  void createImages();
  // Writes every descriptor the path tracer provides into s (a recorder lists them: provided_).
  void writeDescriptors(vk::DescriptorSets& s);
  void updateFrameUniforms();

  vk::Context& ctx_;
  shader::ShaderLibrary& library_;
  const GpuScene& scene_;
  const GpuEnvironment* env_;
  RenderSettings settings_;
  CameraState camera_;
  shader::ShaderLibrary::ProgramId program_ = 0;
  scene::SceneFeatures features_;
  bool cpuDeviceCode_ = false;
  std::vector<std::pair<scene::SceneFeatures, shader::ShaderLibrary::ProgramId>> variants_;
  std::unique_ptr<vk::PipelineLayout> layout_;
  std::unique_ptr<vk::DescriptorSets> sets_;
  std::vector<vk::ProvidedBinding> provided_;  // what writeDescriptors fills: a program may use no more
  uint64_t emitterVersion_ = 0;                // the scene's emitter buffers the descriptors point at
  std::unique_ptr<vk::RtLibraryCache>
      libraries_;  // before pipeline_: destroyed after the pipelines linked from it
  std::unique_ptr<vk::RayTracingPipeline> pipeline_;
  vk::Image accum_, albedo_, normal_, info_;
  vk::Buffer frameUniforms_, counters_, blueNoise_, sobol_;
  uint32_t sampleIndex_ = 0;
  double pipelineMs_ = 0;
  std::atomic<bool> warmupEnabled_{false};
  std::atomic<uint32_t> warmupMismatches_{0};
  WarmupSlot<PathTracerJitWarmup> warmup_;  // made ahead by addHotReloadTarget, used by the reload worker
};

}  // namespace wb::render
