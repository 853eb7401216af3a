// The hybrid renderer: a G-buffer raster pass (dynamic rendering), ray traced sun shadows and ambient
// occlusion from the G-buffer (ray tracing pipeline, no primary rays), optional ray traced reflections for
// smooth surfaces, and a compute composite into linear radiance. Every pipeline comes from the ShaderLibrary
// (compiled, cached, reflected into its layout) and is hot reloadable through live::HotReload.
#pragma once
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "render/hybrid/hybrid_settings.h"
#include "render/renderer.h"
#include "vk/graphics_pipeline.h"
#include "vk/pipeline_layout.h"
#include "vk/rt_pipeline.h"

namespace wb::render {

// The hybrid renderer's passes, in the order a frame runs them. Reflection exists only in
// RenderMode::Reflections.
enum class HybridPass { GBuffer = 0, ShadowAo = 1, Reflection = 2, Composite = 3 };

class HybridRenderer final : public Renderer {
 public:
  static constexpr size_t kPassCount = 4;
  static const char* passName(HybridPass p);
  // Its key in per-pass timings (vk::GpuTimer, `pass_ms`): "gbuffer", "shadow_ao", "reflections",
  // "composite".
  static const char* passKey(HybridPass p);

  // `shaderRoot` is the shaders/ folder (tests point it at a temporary copy); the library's include roots
  // should contain it.
  HybridRenderer(const RendererResources& resources, const RenderSettings& settings, RenderMode mode,
                 const HybridSettings& hybrid,
                 const std::filesystem::path& shaderRoot = std::filesystem::path());
  ~HybridRenderer() override;
  HybridRenderer(const HybridRenderer&) = delete;
  HybridRenderer& operator=(const HybridRenderer&) = delete;

  static std::vector<shader::ShaderKey> stageKeys(HybridPass pass, const std::filesystem::path& shaderRoot);

  bool hasPass(HybridPass p) const { return p != HybridPass::Reflection || mode_ == RenderMode::Reflections; }
  // The pass (it must exist: hasPass()).
  Pass& pass(HybridPass p) const { return *passes_[size_t(p)]; }
  shader::ShaderLibrary::ProgramId program(HybridPass p) const { return pass(p).program(); }

  void setHybridSettings(const HybridSettings& hybrid);
  const HybridSettings& hybridSettings() const { return hybrid_; }

  // Renderer
  RenderMode mode() const override { return mode_; }
  vk::Context& context() const override { return ctx_; }
  void setSettings(const RenderSettings& settings) override;
  const RenderSettings& settings() const override { return settings_; }
  void setCamera(const CameraState& camera) override;  // restarts temporal accumulation
  void setEnvironment(const GpuEnvironment& env) override;
  void setLights(const std::vector<gpu::DirectionalLight>& lights) override;  // the first is the sun
  void resetAccumulation() override { frameIndex_ = 0; }
  // One frame: G-buffer, shadows/AO, reflections, composite.
  void record(VkCommandBuffer cmd) override;
  void advance() override { ++frameIndex_; }
  uint32_t samplesAccumulated() const override { return frameIndex_; }
  // The composited linear radiance.
  const vk::Image& outputImage() const override { return output_; }
  std::vector<Pass*> passes() const override;
  vk::GpuTimer* passTimer() const override { return timer_.get(); }
  std::unique_ptr<Renderer> makeLike(const RendererResources& resources,
                                     const RenderSettings& settings) const override;
  void matchCompiledParameters(const Renderer& other) override;

  // Pipelines installed per pass since construction (the initial build counts as 1).
  uint32_t pipelineBuilds(HybridPass p) const { return pass(p).installs(); }
  VkPipeline pipelineHandle(HybridPass p) const { return pass(p).pipeline().handle(); }

  // Readbacks (they wait for the device).
  std::vector<float> readOutput() const;        // RGBA32F linear radiance
  std::vector<uint8_t> readShadowMask() const;  // R8: 255 = sunlit
  std::vector<uint8_t> readAoMask() const;      // R8: 255 = open
  std::vector<float> readReflection() const;    // RGBA (from half floats): reflected radiance, a = traced

  float aoRadius() const;
  float sunCosAngle() const;  // the sun's cone, as the path tracer's (scene::sunCosAngularRadius)

  // The inspector: records the shadow, AO and reflection rays of one pixel each frame (nullopt: none). Clears
  // the record.
  void setInspectPixel(std::optional<glm::uvec2> pixel);
  std::optional<glm::uvec2> inspectPixel() const { return inspectPixel_; }
  // The record of the last frame (host-visible memory: call when that frame finished).
  gpu::HybridInspectRecord readInspection() const;

 private:
  struct Draw {
    glm::mat4 model;
    uint32_t geometry = 0;
    uint32_t vertexCount = 0;
  };
  void createImages();
  // Sets every resource the hybrid passes bind on each of them.
  void bindResources();
  void updateUniforms();
  RayTracingRecipe reflectionRecipe() const;

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
  gpu::DirectionalLight sun_{};
  bool hasSun_ = false;
  std::vector<Draw> draws_;
  std::array<std::unique_ptr<Pass>, kPassCount> passes_;  // null where !hasPass()
  std::unique_ptr<vk::GpuTimer> timer_;
  vk::Image albedo_, normal_, emissive_, depth_, shadowMask_, aoMask_, history_, reflection_, output_;
  VkSampler nearest_ = VK_NULL_HANDLE;
  vk::Buffer uniforms_;
  vk::Buffer inspect_;
  std::optional<glm::uvec2> inspectPixel_;
  uint32_t frameIndex_ = 0;
};

}  // namespace wb::render
