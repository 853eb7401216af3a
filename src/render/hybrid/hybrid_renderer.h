// The hybrid renderer: a G-buffer raster pass (dynamic rendering), ray traced sun shadows and ambient
// occlusion from the G-buffer (ray tracing pipeline, no primary rays), optional ray traced reflections for
// smooth surfaces, and a compute composite into linear radiance. Every pipeline comes from the ShaderLibrary
// (compiled, cached, reflected into its layout) and is hot reloadable through render::HotReload.
#pragma once
#include <array>
#include <atomic>
#include <filesystem>
#include <memory>
#include <vector>

#include "render/environment.h"
#include "render/gpu_scene.h"
#include "render/hot_reload.h"
#include "render/hybrid/hybrid_settings.h"
#include "render/path_tracer.h"
#include "render/settings.h"
#include "render/warmup_slot.h"
#include "scene/scene.h"
#include "shader/library.h"
#include "vk/graphics_pipeline.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

namespace wb::render {

class HybridJitWarmup;

class HybridRenderer {
 public:
  // The programs, in the order of the passes. Reflection is registered only in RenderMode::Reflections.
  enum class Pass { GBuffer = 0, ShadowAo = 1, Reflection = 2, Composite = 3 };
  static constexpr size_t kPassCount = 4;
  static const char* passName(Pass p);

  // `shaderRoot` is the shaders/ folder (tests point it at a temporary copy); the library's include roots
  // should contain it.
  HybridRenderer(vk::Context& ctx, shader::ShaderLibrary& library, const GpuScene& gpuScene,
                 const scene::Scene& scene, const GpuEnvironment& env, const RenderSettings& settings,
                 RenderMode mode, const HybridSettings& hybrid,
                 const std::filesystem::path& shaderRoot = std::filesystem::path());
  ~HybridRenderer();
  HybridRenderer(const HybridRenderer&) = delete;
  HybridRenderer& operator=(const HybridRenderer&) = delete;

  static std::vector<shader::ShaderKey> stageKeys(Pass pass, const std::filesystem::path& shaderRoot);

  RenderMode mode() const { return mode_; }
  bool hasPass(Pass p) const { return p != Pass::Reflection || mode_ == RenderMode::Reflections; }
  shader::ShaderLibrary::ProgramId program(Pass p) const { return programs_[size_t(p)]; }

  void setCamera(const CameraState& camera);  // restarts temporal accumulation
  void setSettings(const RenderSettings& settings);
  void setHybridSettings(const HybridSettings& hybrid);
  // The live window's edits: a new environment (waits for the device) and the sun (the first light).
  void setEnvironment(const GpuEnvironment& env);
  void setLights(const std::vector<gpu::DirectionalLight>& lights);
  const HybridSettings& hybridSettings() const { return hybrid_; }
  const RenderSettings& settings() const { return settings_; }
  void resetAccumulation() { frameIndex_ = 0; }
  uint32_t framesAccumulated() const { return frameIndex_; }

  // Records one frame (G-buffer, shadows/AO, reflections, composite) into cmd; call advanceFrame() after it
  // ran.
  void record(VkCommandBuffer cmd);
  void advanceFrame() { ++frameIndex_; }
  // Renders `frames` frames, submitting and waiting for each; returns each frame's wall time in seconds.
  std::vector<double> render(uint32_t frames);

  // Hot reload: prepare (any thread) and commit (render thread, frame boundary), per pass.
  std::shared_ptr<void> preparePipeline(Pass pass, const shader::ShaderLibrary::ProgramBuild& build) const;
  void commitPipeline(Pass pass, std::shared_ptr<void> prepared);
  // Registers one HotReload target per program ("hybrid gbuffer (raster)", "hybrid shadow+ao (ray
  // tracing)"...).
  void addHotReloadTargets(HotReload& hot);
  // Pipelines committed per pass since construction (the initial build counts as 1).
  uint32_t pipelineBuilds(Pass p) const { return builds_[size_t(p)]; }
  VkPipeline pipelineHandle(Pass p) const;
  // As the path tracer's: hot reloads on a lazily compiling driver compile the new pipeline ahead on a second
  // device (render/jit_warmup.h).
  bool jitWarmupEnabled() const { return warmupEnabled_; }
  bool jitWarmupPresent() const { return warmup_.present(); }  // as the path tracer's
  uint32_t jitWarmups() const;
  uint32_t jitWarmupMismatches() const { return warmupMismatches_; }
  // The ray tracing passes' group handles (empty for the raster and compute passes).
  std::vector<uint8_t> groupHandles(Pass p) const;

  // The composited linear radiance (RGBA32F storage image, GENERAL layout), e.g. for a display pass.
  const vk::Image& outputImage() const { return output_; }

  // Readbacks (they wait for the device).
  std::vector<float> readOutput() const;        // RGBA32F linear radiance
  std::vector<uint8_t> readShadowMask() const;  // R8: 255 = sunlit
  std::vector<uint8_t> readAoMask() const;      // R8: 255 = open
  std::vector<float> readReflection() const;    // RGBA (from half floats): reflected radiance, a = traced

  float aoRadius() const;
  float sunCosAngle() const;

 private:
  struct Prepared;
  struct Draw {
    glm::mat4 model;
    uint32_t geometry = 0;
    uint32_t vertexCount = 0;
  };
  void createImages();
  // Writes every descriptor the hybrid passes provide into s (a recorder lists them: provided_).
  void writeDescriptors(vk::DescriptorSets& s);
  void updateUniforms();
  VkPipelineBindPoint bindPoint(Pass pass) const;

  vk::Context& ctx_;
  shader::ShaderLibrary& library_;
  const GpuScene& gpuScene_;
  const GpuEnvironment* env_;
  RenderSettings settings_;
  RenderMode mode_;
  HybridSettings hybrid_;
  std::filesystem::path shaderRoot_;
  CameraState camera_;
  float cameraDistance_ = 1.0f;
  float sceneSunCos_ = 1.0f;
  gpu::DirectionalLight sun_{};
  bool hasSun_ = false;
  std::vector<Draw> draws_;
  std::array<shader::ShaderLibrary::ProgramId, kPassCount> programs_{};
  std::array<std::unique_ptr<Prepared>, kPassCount> pipelines_;
  std::array<std::unique_ptr<vk::DescriptorSets>, kPassCount> sets_;
  std::vector<vk::ProvidedBinding> provided_;  // what writeDescriptors fills: a program may use no more
  std::array<uint32_t, kPassCount> builds_{};
  vk::Image albedo_, normal_, emissive_, depth_, shadowMask_, aoMask_, history_, reflection_, output_;
  VkSampler nearest_ = VK_NULL_HANDLE;
  vk::Buffer uniforms_;
  uint32_t frameIndex_ = 0;
  std::atomic<bool> warmupEnabled_{false};
  std::atomic<uint32_t> warmupMismatches_{0};
  WarmupSlot<HybridJitWarmup> warmup_;  // made ahead by addHotReloadTargets, used by the reload worker
};

}  // namespace wb::render
