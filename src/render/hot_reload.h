// Hot reload for the render loop: the shader Reloader compiles changed programs on its thread, this class's
// worker builds their pipelines (still off the frame path), and the render thread commits them at a frame
// boundary. Failures keep the last good pipeline and are kept as the current error until a later success.
#pragma once
#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "render/reload_frames.h"
#include "shader/reloader.h"
#include "vk/rt_pipeline.h"

namespace wb::render {

// On a CPU device (lavapipe) the frames and a rebuild's compiles share the cores: while a rebuild compiles,
// `watch` keeps this share of the CPU for its frames (it rests between frames; the window traces with this
// share of its budget and rests to kWindowShareWhileCompiling below) so the edit reaches the screen sooner.
// The frames drawn meanwhile are thrown away at the swap anyway (accumulation restarts). GPUs render beside
// the CPU's compile: they keep everything. Measured on lavapipe (bench --only reload, 2 x 8 edits,
// alternating): a 0.1 share reaches the first new frame as soon as no warm-up at all (1321 vs 1324 ms mean of
// the p50s), 0.25 took 80 ms longer.
inline constexpr double kCpuRenderShareWhileCompiling = 0.1;
// The live window keeps a larger share, so it still answers input (~10 frames/s) while a rebuild compiles.
// Measured with bench/window_reload.sh (8 edits, 2 rounds, alternating; edit to first new frame p50): share
// 0.25 1604 and 1268 ms at ~10 frames/s, share 0.1 2026 and 1367 ms at ~3 frames/s, no rest 2639 and 3048 ms.
inline constexpr double kWindowShareWhileCompiling = 0.25;
// After a frame that took frameMs, a render loop on a CPU device rests frameMs times this while a rebuild
// compiles (its frames then keep `share` of the time); 0 on GPUs. WB_REBUILD_YIELD=R sets the ratio (0: never
// rest; empty: the default).
double rebuildRestRatio(bool cpuDevice, double share = kCpuRenderShareWhileCompiling);

// One reload as the UI history and the `watch` log show it.
struct ReloadEvent {
  std::vector<std::string> filesChanged;
  std::vector<std::string> stagesRecompiled;
  std::vector<std::string> pipelinesRebuilt;
  double compileMs = 0;   // glslang (+ cache) time of the rebuild
  double pipelineMs = 0;  // Vulkan pipeline creation
  // Ray tracing pipelines linked from per-group libraries (GPUs; all zero when they are monolithic): how many
  // libraries the rebuild compiled and reused, its slowest library compile and the link.
  vk::RtLibraryStats libraries;
  double editToNewPipelineMs = 0;  // change seen on disk -> pipeline committed
  double editToFirstFrameMs = -1;  // change seen on disk -> first frame with the new pipeline finished
  bool ok = true;
  std::string error;  // file:line: error: message lines
  std::chrono::system_clock::time_point when;
  std::chrono::steady_clock::time_point editSeen;  // when the watcher saw the change
  // The render loop's frames around it (filled with the first new frame, or at once when nothing was
  // rebuilt).
  ReloadFrameStats frames;
};

class HotReload {
 public:
  // A pipeline owner: `prepare` builds a pipeline from a program build on the worker thread and returns it
  // type-erased; `commit` installs it on the render thread.
  struct Target {
    std::string name;
    std::function<std::shared_ptr<void>(const shader::ShaderLibrary::ProgramBuild&)> prepare;
    std::function<void(std::shared_ptr<void>)> commit;
    // Optional: what a prepared pipeline's library build took (summed into ReloadEvent::libraries).
    std::function<vk::RtLibraryStats(const std::shared_ptr<void>&)> libraryStats;
  };

  HotReload(shader::ShaderLibrary& library, std::vector<std::filesystem::path> watchDirs);
  ~HotReload();
  HotReload(const HotReload&) = delete;
  HotReload& operator=(const HotReload&) = delete;

  void addTarget(shader::ShaderLibrary::ProgramId program, Target target);
  void start();
  void stop();

  // Render thread, at a frame boundary: commits prepared pipelines. Returns the event it applied, if any.
  std::optional<ReloadEvent> poll();
  // Render thread, once per frame: a frame finished; the first after a commit used the new pipelines (fills
  // editToFirstFrameMs and the event's frame times). frameBegin: when the frame's work began (default: the
  // previous call, for loops that draw back to back; pass it when the loop also waits between frames).
  void frameFinished(std::optional<std::chrono::steady_clock::time_point> frameBegin = std::nullopt);

  void setAutoReload(bool on) { autoReload_ = on; }
  bool autoReload() const { return autoReload_; }
  void reloadAll();  // rebuild every program now (the UI's reload button)

  // While a change is being compiled or its pipelines built (not yet waiting for the commit): on a CPU device
  // the render loop yields part of the cores to it (its frames are thrown away at the swap anyway).
  bool compiling() const { return reloader_.rebuilding() || preparing_; }

  std::vector<ReloadEvent> history() const;
  std::string currentError() const;  // empty when the last reload of every program succeeded

 private:
  struct Pending {
    ReloadEvent event;
    std::vector<std::pair<shader::ShaderLibrary::ProgramId, std::shared_ptr<void>>> prepared;
    std::chrono::steady_clock::time_point editTime;
  };
  void run();

  shader::ShaderLibrary& library_;
  shader::Reloader reloader_;
  std::map<shader::ShaderLibrary::ProgramId, Target> targets_;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> autoReload_{true};
  std::atomic<bool> manualRequest_{false};
  std::atomic<bool> preparing_{false};
  mutable std::mutex mutex_;
  std::deque<Pending> pending_;
  std::vector<ReloadEvent> history_;
  std::map<shader::ShaderLibrary::ProgramId, std::string> errors_;
  std::optional<std::chrono::steady_clock::time_point> awaitingFrame_;
  ReloadFrameTimeline frameTimeline_;  // render thread only
  std::optional<std::chrono::steady_clock::time_point> lastFrameEnd_;
};

}  // namespace wb::render
