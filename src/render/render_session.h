// Everything a render needs, built in order: device, shader library, scene on the device, environment, and a
// renderer per mode (the path tracer always; the hybrid modes' on first use). Used by the commands, the
// window and the GPU tests.
#pragma once
#include <array>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/image.h"
#include "render/hybrid/hybrid_renderer.h"
#include "render/path_tracer.h"
#include "scene/scene.h"
#include "shader/library.h"
#include "vk/context.h"

namespace wb::render {

struct SessionOptions {
  std::string scenePath;                  // empty = default scene
  std::optional<scene::Scene> sceneData;  // a scene built in code (tests); used instead of scenePath
  RenderSettings settings;
  vk::ContextOptions context;
  std::filesystem::path cacheDir;  // empty = shader_cache/ of the project
  bool quiet = false;              // true: the scene's and environment's warnings are not printed (stderr)
  RenderMode mode = RenderMode::PathTrace;  // the renderer render() and image() use
  HybridSettings hybrid;
};

EnvironmentData loadEnvironmentData(const RenderSettings& settings);
// The shader specialisation for a scene and the environment the settings ask for (generic with --generic).
scene::SceneFeatures featuresFor(const scene::Scene& scene, const RenderSettings& settings);

// A hash of every file under shaders/ (names and contents): part of the key of anything cached from a render
// (the references of `converge` and `bench`), so a renderer change never reuses a stale image.
std::string shaderSourceFingerprint();

// What a session's owner does with each renderer it makes.
struct RendererHooks {
  // Render thread: a renderer is made, or taken from the worker that made it (prepareMode).
  std::function<void(Renderer&)> adopted;
  // The worker making a renderer off the render loop (prepareMode), before it is handed over: work that
  // should not happen on the loop (compiling its pipelines ahead where the driver compiles at the first
  // dispatch). Its failure is a warning; the renderer is used as it is.
  std::function<void(Renderer&)> prepare;
};

class RenderSession {
 public:
  explicit RenderSession(const SessionOptions& options);
  ~RenderSession();
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  vk::Context& context() { return *ctx_; }
  const vk::Context& context() const { return *ctx_; }
  shader::ShaderLibrary& library() { return *library_; }
  const scene::Scene& scene() const { return scene_; }
  GpuScene& gpuScene() { return *gpuScene_; }
  const GpuEnvironment& environment() const { return *env_; }
  const CameraState& sceneCamera() const { return sceneCamera_; }
  double setupSeconds() const { return setupSeconds_; }

  // The current mode and its renderer.
  RenderMode mode() const { return mode_; }
  Renderer& renderer() { return *renderers_[size_t(mode_)]; }
  const Renderer& renderer() const { return *renderers_[size_t(mode_)]; }
  // Makes `mode` current; its renderer is made on first use with `settings` (the size included) and the
  // session's camera, environment, lights and hybrid settings.
  Renderer& setMode(RenderMode mode, const RenderSettings& settings);
  // The renderer of `mode`, or nullptr when it has not been made.
  Renderer* rendererFor(RenderMode mode) { return renderers_[size_t(mode)].get(); }
  // Starts making `mode`'s renderer on a worker thread (unless it is made or being made), so that a frame
  // loop keeps drawing the current mode while the other one's pipelines are created (and, with a hot reload
  // hooks set, prepared by RendererHooks::prepare, e.g. compiled ahead). Render thread only.
  void prepareMode(RenderMode mode, const RenderSettings& settings);
  // Whether `mode`'s renderer is made; one the worker finished is taken here and given the session's camera,
  // lights and hot reload. Rethrows the worker's failure. Render thread only.
  bool modeReady(RenderMode mode);
  // Every renderer made so far, the path tracer first.
  void forEachRenderer(const std::function<void(Renderer&)>& f);
  // The path tracer (always made: the AOVs, debug views and pixel statistics are its).
  PathTracer& pathTracer() { return static_cast<PathTracer&>(*renderers_[0]); }
  const PathTracer& pathTracer() const { return static_cast<const PathTracer&>(*renderers_[0]); }
  // The hybrid renderer of the current mode (nullptr in pathtrace mode).
  HybridRenderer* hybrid();

  // Parameters every renderer shares: set on all of those made (and on those made later).
  void setCamera(const CameraState& camera);
  const CameraState& camera() const { return camera_; }
  // Loads the environment the settings name (envPath or envColor) and points every renderer at it. Throws
  // std::runtime_error with the reason, keeping the current one.
  void setEnvironment(const RenderSettings& settings);
  void setLights(const std::vector<gpu::DirectionalLight>& lights);
  const std::vector<gpu::DirectionalLight>& lights() const { return lights_; }
  void setHybridSettings(const HybridSettings& hybrid);
  const HybridSettings& hybridSettings() const { return hybrid_; }

  // What is done with every renderer the session makes, now and later (the live-edit loop registers its
  // passes); empty hooks detach (whoever set them must outlive the session's renderers or detach first).
  void setRendererHooks(RendererHooks hooks);

  // Renders `spp` samples with the current renderer from scratch (hybrid modes: `spp` frames, shadows/AO
  // averaged over them); returns the wall time in seconds. frameSeconds() has each sample's.
  double render(uint32_t spp, const Renderer::Progress& progress = {});
  const std::vector<double>& frameSeconds() const { return frameSeconds_; }
  eval::ImageRGBA image() const { return renderer().readImage(); }  // alpha = 1
  eval::ImageRGBA aov(Aov which) const;

 private:
  RendererResources resources() const;
  std::unique_ptr<Renderer> makeRenderer(RenderMode mode, const RenderSettings& settings);
  // The part of makeRenderer a worker thread may run: reads only what does not change while it runs.
  std::unique_ptr<Renderer> constructRenderer(RenderMode mode, const RenderSettings& settings,
                                              const HybridSettings& hybrid) const;
  void adopt(Renderer& r);
  void finishPreparing();  // waits for every renderer being made and takes it

  std::unique_ptr<vk::Context> ctx_;
  std::unique_ptr<shader::ShaderLibrary> library_;
  scene::Scene scene_;
  std::unique_ptr<GpuScene> gpuScene_;
  std::unique_ptr<GpuEnvironment> env_;
  // By RenderMode; [0] (the path tracer) always made. Declared after the resources: destroyed first.
  std::array<std::unique_ptr<Renderer>, 3> renderers_;
  std::array<std::future<std::unique_ptr<Renderer>>, 3> preparing_;  // renderers being made by a worker
  RenderMode mode_ = RenderMode::PathTrace;
  HybridSettings hybrid_;
  CameraState camera_, sceneCamera_;
  std::vector<gpu::DirectionalLight> lights_;
  RendererHooks hooks_;
  bool quiet_ = false;
  std::vector<double> frameSeconds_;
  double setupSeconds_ = 0;
};

}  // namespace wb::render
