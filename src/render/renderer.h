// What every renderer is to the code that drives it (the commands, the window, the bench, the tests and hot
// reload): parameters, camera, environment, render N samples, the output image, its pipelines' programs for
// hot reload, and statistics. The path tracer and the hybrid renderer implement it; RenderSession holds one
// per mode.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

#include "eval/image.h"
#include "render/environment.h"
#include "render/gpu_scene.h"
#include "render/pass.h"
#include "vk/gpu_timer.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "shader/library.h"
#include "shared/gpu_types.h"

namespace wb::render {

struct CameraState {
  glm::mat4 view{1.0f};  // world to camera
  float yfov = 0.7f;
  float znear = 0.01f;
};
CameraState cameraFromScene(const scene::Camera& camera);

// What a renderer is made on: the device, the shader library, the scene (on the host and on the device) and
// the environment. All must outlive the renderer (the environment: or the next setEnvironment).
struct RendererResources {
  vk::Context& ctx;
  shader::ShaderLibrary& library;
  const scene::Scene& scene;
  const GpuScene& gpuScene;
  const GpuEnvironment& environment;
};

// The texels of an RGBA32F image in GENERAL layout, read back (waits for the device).
std::vector<float> readFloatImage(const vk::Image& image);

class Renderer {
 public:
  virtual ~Renderer() = default;
  virtual RenderMode mode() const = 0;
  virtual vk::Context& context() const = 0;

  // Parameters; every call restarts accumulation (unchanged settings too), except the path tracer's when only
  // `denoise` changed. setSettings resizes the images when the size changed.
  virtual void setSettings(const RenderSettings& settings) = 0;
  virtual const RenderSettings& settings() const = 0;
  virtual void setCamera(const CameraState& camera) = 0;
  // Points at another environment (waits for the device); it must outlive the renderer or the next call.
  virtual void setEnvironment(const GpuEnvironment& env) = 0;
  // The scene's directional lights changed (GpuScene's buffer holds them already).
  virtual void setLights(const std::vector<gpu::DirectionalLight>& lights) = 0;
  virtual void resetAccumulation() = 0;

  // Records one sample (the path tracer) or frame (the hybrid modes) of the whole image into cmd; advance()
  // once it ran.
  virtual void record(VkCommandBuffer cmd) = 0;
  virtual void advance() = 0;
  // Records up to `samples` samples (at least one) into cmd and advances past them; returns how many. The
  // path tracer traces several in one launch where its settings or device ask for it (samplesPerLaunch).
  virtual uint32_t recordBatch(VkCommandBuffer cmd, uint32_t samples) {
    (void)samples;
    record(cmd);
    advance();
    return 1;
  }
  // Records the dispatches of one sample with as little work as the renderer allows (the path tracer traces
  // zero rays): on a driver that compiles at the first dispatch this compiles every pipeline the sample uses
  // without running the shaders (the JIT warm-up).
  virtual void recordCompileOnly(VkCommandBuffer cmd) { record(cmd); }
  // Samples (frames) in the current accumulation.
  virtual uint32_t samplesAccumulated() const = 0;
  // Called after each sample with the samples done and the seconds so far; returning false stops the render.
  using Progress = std::function<bool(uint32_t done, double seconds)>;
  // Renders `samples` samples, submitting and waiting for each batch (recordBatch); returns each one's wall
  // time in seconds, a batch's shared equally among its samples (fewer than `samples` when `progress` stopped
  // it).
  std::vector<double> render(uint32_t samples, const Progress& progress = {});

  // Linear radiance (RGBA32F storage image, GENERAL layout), for a display pass.
  virtual const vk::Image& outputImage() const = 0;
  // The same read back (waits for the device); alpha = 1.
  virtual eval::ImageRGBA readImage() const;
  // The estimator's own image, before any filter of its output (the path tracer's denoiser): what the A/B
  // comparison judges. The same as readImage() for a renderer without one.
  virtual eval::ImageRGBA readEstimate() const { return readImage(); }

  // Its passes, in a fixed order: a renderer made with makeLike() lists the same passes in the same order
  // (the live-edit loop, the JIT warm-up and the A/B comparison address a pass by its index).
  virtual std::vector<Pass*> passes() const = 0;
  // Pipelines installed into its passes since construction (the initial builds count).
  uint32_t pipelineInstalls() const;
  // A renderer of the same kind, mode and shader variant on other resources, with `settings` (the JIT
  // warm-up's stand-in on a second device, the A/B comparison's at its own size).
  virtual std::unique_ptr<Renderer> makeLike(const RendererResources& resources,
                                             const RenderSettings& settings) const = 0;
  // Copies from `other` (of the same kind) the parameters that are compiled into pipelines (specialisation
  // constants), before a pipeline of this renderer is built to match one of `other`'s.
  virtual void matchCompiledParameters(const Renderer& other) { (void)other; }

  // GPU time per pass: record() brackets each pass it records (vk/gpu_timer.h). The caller collects a
  // round once its submission finished (render() does after each batch). nullptr: not timed.
  virtual vk::GpuTimer* passTimer() const { return nullptr; }

  // What the shaders counted since resetCounters() (paths, rays, NaN/Inf samples dropped); all zero for a
  // renderer that does not count.
  virtual gpu::Counters readCounters() const { return {}; }
  virtual void resetCounters() {}
};

}  // namespace wb::render
