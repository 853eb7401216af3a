// Hot reload for the render loop: the shader Reloader compiles changed programs on its thread, this class's
// worker builds their pipelines (still off the frame path), and the render thread installs them at a frame
// boundary. Failures keep the last good pipeline and are kept as the current error until a later success.
// Where the device's policy asks for it (DevicePolicy::jitWarmup), a renderer's new pipelines are also
// compiled ahead on a warm-up device (render/jit_warmup.h) before they are installed.
#pragma once
#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "eval/ab.h"
#include "live/jit_warmup.h"
#include "live/reload_frames.h"
#include "render/pass.h"
#include "render/render_session.h"
#include "render/renderer.h"
#include "live/warmup_slot.h"
#include "live/reloader.h"

namespace wb::live {

// The A/B comparison of one rebuilt pipeline (render/ab_comparison.h): old against new at the A/B budget.
struct ReloadAB {
  std::string pipeline;  // the target's name ("pathtracer", "hybrid: shadow/AO", ...)
  std::string mode;      // the renderer's mode ("pathtrace", "hybrid", "reflections")
  bool active = false;   // the renderer on screen
  eval::ImageComparison image;
  eval::SpeedComparison speed;
};

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
  // The A/B comparisons of the rebuilt pipelines (empty when none ran), the active renderer's first, and
  // their total wall time (-1: none ran).
  std::vector<ReloadAB> ab;
  double abMs = -1;
  bool reverted = false;  // the old pipelines were reinstalled (the A/B panel's Revert)
};

class HotReload {
 public:
  // A pass whose new pipeline poll() installed: the pipeline (and build) it replaced, kept alive until the
  // next reload (the A/B comparison renders with it, a revert reinstalls it), and the new one.
  struct InstalledPass {
    render::ReloadTarget* pass = nullptr;
    render::Renderer* owner = nullptr;  // the renderer the pass belongs to (addRenderer), else nullptr
    size_t passIndex = 0;               // its index in owner->passes()
    std::string name;
    render::PassPipeline before, after;
  };
  // The JIT warm-up of one renderer's reloads.
  struct WarmupStats {
    bool enabled = false;     // the device's policy asks for it
    bool present = false;     // the warm-up device exists or is being made
    uint32_t warmups = 0;     // pipelines compiled ahead
    uint32_t mismatches = 0;  // warmed pipelines whose groups got other numbers (the first frame compiled)
    uint32_t failures = 0;    // warm-ups that threw (that reload's first frame compiled)
    uint32_t hung = 0;        // trial frames that never finished (their reloads refused)
  };

  HotReload(shader::ShaderLibrary& library, std::vector<std::filesystem::path> watchDirs);
  ~HotReload();
  HotReload(const HotReload&) = delete;
  HotReload& operator=(const HotReload&) = delete;

  // A pass to reload (it must outlive this object): a compiled change of its program (whichever variant it
  // uses at the time) is built into a pipeline on the worker and installed by poll().
  void addPass(render::ReloadTarget& pass);
  // Every pass of `renderer` (those added already are skipped), reloaded with the JIT warm-up where the
  // device's policy asks for it (DevicePolicy::jitWarmup: its warm-up device starts being made now, on a
  // low-priority thread, so that the first edit does not wait for it) and compared by the A/B comparison.
  // `renderer` must outlive this object.
  void addRenderer(render::Renderer& renderer);
  WarmupStats jitWarmup(const render::Renderer& renderer) const;
  // With DevicePolicy::jitWarmup: rebuilds each of `renderer`'s pipelines beside a warm-up of it (as a reload
  // does), so that its first frame loads the machine code from Mesa's cache instead of compiling on the
  // render loop. For a renderer made off the loop (a mode being prepared), before addRenderer; blocks for the
  // compile. Nothing to do on other devices. Throws what the compile and pipeline creation throw.
  void compileAhead(render::Renderer& renderer);
  // For RenderSession::setRendererHooks: every renderer the session makes is added (addRenderer), and one
  // made off the render loop is compiled ahead (compileAhead).
  render::RendererHooks sessionHooks();
  void start();
  void stop();

  // Render thread, at a frame boundary: installs the prepared pipelines that no newer save has superseded
  // (the pass's program changed since the compile they were built from: a newer build is on its way).
  // Returns the event it applied, if any.
  std::optional<ReloadEvent> poll();
  // Render thread: the passes the latest poll() that applied an event installed into (those of a renderer
  // added with addRenderer); cleared by the next such poll().
  const std::vector<InstalledPass>& lastInstalled() const { return lastInstalled_; }
  // Render thread: attaches A/B results to the newest event of the history.
  void attachAB(std::vector<ReloadAB> ab, double ms);
  // Render thread: reinstalls the pipelines `installed` replaced (kept, so nothing is built); the newest
  // event is marked reverted. The files on disk are not touched; until each is saved again, builds read the
  // text the old pipelines were compiled from (ShaderLibrary::keepSourcesOf), so a variant built later is
  // the reverted code too. Returns the files whose old text is no longer known (builds read them from disk).
  std::vector<std::filesystem::path> revert(const std::vector<InstalledPass>& installed);
  // Render thread, once per frame: a frame finished; the first after a commit used the new pipelines (fills
  // editToFirstFrameMs and the event's frame times). frameBegin: when the frame's work began (default: the
  // previous call, for loops that draw back to back; pass it when the loop also waits between frames).
  void frameFinished(std::optional<std::chrono::steady_clock::time_point> frameBegin = std::nullopt);

  // Called on the worker thread when pipelines are ready for poll() (or a reload event without pipelines):
  // a render loop that sleeps between frames wakes up to commit them (the window posts an empty event).
  void setOnReady(std::function<void()> onReady) { onReady_ = std::move(onReady); }

  void setAutoReload(bool on) { autoReload_ = on; }
  bool autoReload() const { return autoReload_; }
  void reloadAll();  // rebuild every program now (the UI's reload button)

  // From the moment a change is seen until its pipelines are built (not yet waiting for the commit): on a CPU
  // device the render loop yields part of the cores to it (its frames are thrown away at the swap anyway), so
  // no frame starts between the save and the compile.
  bool compiling() const { return reloader_.newerChange() || preparing_; }
  // A change is seen and not yet compiled, a rebuild is compiling, or its pipelines wait for poll().
  bool busy() const;

  // What the reload in flight is doing, for the window's indicator.
  struct Status {
    enum class Stage { Idle, Compiling, BuildingPipelines, Installing } stage = Stage::Idle;
    double elapsedMs = 0;     // since the stage's reload began (the compile's start)
    uint64_t superseded = 0;  // builds dropped for a newer save, since start
  };
  Status status() const;
  static const char* stageName(Status::Stage s);

  std::vector<ReloadEvent> history() const;
  std::optional<ReloadEvent> lastEvent() const;  // the newest of history() without copying the rest
  std::string currentError() const;              // empty when the last reload of every program succeeded

 private:
  struct Warmup {
    bool enabled = false;       // a warm-up device: JIT compile-ahead or trial frames (the device policy's)
    bool compileAhead = false;  // DevicePolicy::jitWarmup
    std::atomic<uint32_t> mismatches{0}, failures{0};
    WarmupSlot<JitWarmup> slot;
  };
  // A pass being reloaded; its address is stable (entries_ holds them by pointer).
  struct Entry {
    render::ReloadTarget* pass = nullptr;
    render::Renderer* owner = nullptr;
    size_t passIndex = 0;
    Warmup* warmup = nullptr;  // owner's (null without an owner)
  };
  struct Built {
    Entry* entry = nullptr;
    render::PassPipeline pipeline;
  };
  struct Pending {
    ReloadEvent event;
    std::vector<Built> built;
    uint64_t sequence = 0;  // the compile's (ReloadResult::sequence)
    std::chrono::steady_clock::time_point editTime;
  };
  void run();
  // Builds the pipelines of one compile result; false when a newer save superseded all of it.
  bool prepare(ReloadResult& result);
  Warmup* warmupFor(const render::Renderer& renderer);  // made on first use
  render::PassPipeline buildWithWarmup(const Entry& entry, shader::ShaderLibrary::ProgramId program,
                                       const shader::ShaderLibrary::ProgramBuild& build);
  std::vector<Entry*> entries() const;

  shader::ShaderLibrary& library_;
  Reloader reloader_;
  std::function<void()> onReady_;                // set before start()
  std::vector<std::unique_ptr<Entry>> entries_;  // guarded by mutex_
  std::map<const render::Renderer*, std::unique_ptr<Warmup>>
      warmups_;  // guarded by mutex_; entries live as long
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> autoReload_{true};
  std::atomic<bool> manualRequest_{false};
  std::atomic<bool> preparing_{false};
  std::atomic<std::chrono::steady_clock::rep> prepareStart_{0};
  std::atomic<uint64_t> superseded_{0};
  std::set<std::string> carriedFiles_;  // files of superseded results, reported with the next event
  mutable std::mutex mutex_;
  std::set<shader::ShaderLibrary::ProgramId> pipelineFailed_;  // last pipeline build failed
  std::deque<Pending> pending_;
  std::vector<ReloadEvent> history_;
  std::map<shader::ShaderLibrary::ProgramId, std::string> errors_;
  std::optional<std::chrono::steady_clock::time_point> awaitingFrame_;
  ReloadFrameTimeline frameTimeline_;         // render thread only
  std::vector<InstalledPass> lastInstalled_;  // render thread only
  std::optional<std::chrono::steady_clock::time_point> lastFrameEnd_;
};

}  // namespace wb::live
