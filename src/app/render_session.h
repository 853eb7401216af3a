// Everything a render needs, built in order: device, shader library, scene on the device, environment, and
// the path tracer. Used by the headless commands, the window and the GPU tests.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "eval/image.h"
#include "render/hybrid/hybrid_renderer.h"
#include "render/path_tracer.h"
#include "scene/scene.h"
#include "shader/library.h"
#include "vk/context.h"

namespace wb::app {

struct SessionOptions {
  std::string scenePath;                  // empty = default scene
  std::optional<scene::Scene> sceneData;  // a scene built in code (tests); used instead of scenePath
  render::RenderSettings settings;
  vk::ContextOptions context;
  std::filesystem::path cacheDir;  // empty = shader_cache/ of the project
  bool quiet = false;              // true: the scene's and environment's warnings are not printed (stderr)
  // What render() and image() use: the path tracer, or a hybrid renderer built beside it.
  render::RenderMode mode = render::RenderMode::PathTrace;
  render::HybridSettings hybrid;
};

render::EnvironmentData loadEnvironmentData(const render::RenderSettings& settings);
// The shader specialisation for a scene and the environment the settings ask for (generic with --generic).
scene::SceneFeatures featuresFor(const scene::Scene& scene, const render::RenderSettings& settings);

// A hash of every file under shaders/ (names and contents): part of the key of anything cached from a render
// (the references of `converge` and `bench`), so a renderer change never reuses a stale image.
std::string shaderSourceFingerprint();

class RenderSession {
 public:
  explicit RenderSession(const SessionOptions& options);
  ~RenderSession();

  vk::Context& context() { return *ctx_; }
  shader::ShaderLibrary& library() { return *library_; }
  const scene::Scene& scene() const { return scene_; }
  render::PathTracer& pathTracer() { return *tracer_; }
  render::GpuScene& gpuScene() { return *gpuScene_; }
  const render::GpuEnvironment& environment() const { return *env_; }
  const render::CameraState& sceneCamera() const { return sceneCamera_; }
  double setupSeconds() const { return setupSeconds_; }

  render::RenderMode mode() const { return mode_; }
  // The hybrid renderer (modes hybrid and reflections; nullptr in pathtrace mode).
  render::HybridRenderer* hybrid() { return hybrid_.get(); }

  // Renders `spp` samples from scratch (hybrid modes: `spp` frames, shadows/AO averaged over them); returns
  // the wall time in seconds.
  double render(uint32_t spp);
  // Wall time of each sample / frame of the last render().
  const std::vector<double>& frameSeconds() const { return frameSeconds_; }
  eval::ImageRGBA image() const;  // the accumulation or the hybrid output (alpha = 1)
  eval::ImageRGBA aov(render::Aov which) const;

 private:
  std::unique_ptr<vk::Context> ctx_;
  std::unique_ptr<shader::ShaderLibrary> library_;
  scene::Scene scene_;
  std::unique_ptr<render::GpuScene> gpuScene_;
  std::unique_ptr<render::GpuEnvironment> env_;
  std::unique_ptr<render::PathTracer> tracer_;
  std::unique_ptr<render::HybridRenderer> hybrid_;
  render::RenderMode mode_ = render::RenderMode::PathTrace;
  std::vector<double> frameSeconds_;
  render::CameraState sceneCamera_;
  double setupSeconds_ = 0;
};

}  // namespace wb::app
