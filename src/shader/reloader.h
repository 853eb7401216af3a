// Hot reload: a worker thread watches the shader directories (inotify on directories), coalesces bursts of
// events (a short quiet period, and never while a file is still being written), maps changed files to
// programs through the include graph, rebuilds them off the caller's thread and publishes the results.
#pragma once
#include "shader/library.h"

#include <atomic>
#include <chrono>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

namespace wb::shader {

// Lowers the calling thread's scheduling priority (nice +10, Linux threads have their own): background
// compiles and pipeline builds then take the CPU only when the render loop and lavapipe's threads leave it.
// Measured on lavapipe (`bench --only reload --edits 10`, alternating): frames during a rebuild 1.18-1.27x
// the frame before (p50) at nice 10, 2.0x at nice 0, for edits 12-17% slower. It cannot be undone (raising a
// priority needs privileges). The kernel's autogroups confine nice to a session: busy programs started from
// another terminal share the CPU with the whole workbench; ones started from the same session starve its
// rebuild threads (two busy loops: 12.9 s per edit instead of ~1.1 s; docs/bench/README.md).
void lowerThreadPriority();

struct ReloadResult {
  std::vector<fs::path> filesChanged;
  std::vector<std::string> stagesRecompiled;       // stage file paths (+ " [K=V,...]") whose SPIR-V changed
  std::vector<ShaderLibrary::ProgramId> programs;  // rebuilt successfully, parallel to builds
  std::vector<ShaderLibrary::ProgramBuild> builds;
  std::vector<ShaderLibrary::ProgramId> failedPrograms;  // keep their old pipelines
  double compileMs = 0;                                  // wall time of the rebuild
  bool ok = true;
  std::string error;                               // file:line: severity: message lines of every failure
  std::chrono::steady_clock::time_point editTime;  // when the first change of the burst was seen
};

class Reloader {
 public:
  struct Timing {
    std::chrono::milliseconds quiet{50};           // no events for this long = the burst is over
    std::chrono::milliseconds writeGrace{1000};    // wait this long for a file still open for writing
    std::chrono::milliseconds recreateGrace{300};  // wait this long for a deleted dependency to reappear
  };
  Reloader(ShaderLibrary& lib, std::vector<fs::path> watchDirs);
  Reloader(ShaderLibrary& lib, std::vector<fs::path> watchDirs, Timing timing);
  ~Reloader();
  Reloader(const Reloader&) = delete;
  Reloader& operator=(const Reloader&) = delete;

  // Adds the watches and records the programs' current stages (synchronously), then starts the worker.
  void start();
  void stop();
  std::optional<ReloadResult> poll();  // non-blocking; one result per coalesced change
  void requestReloadAll();
  uint64_t reloadCount() const { return reloads_; }
  bool rebuilding() const { return rebuilding_; }  // a coalesced change is being compiled right now

 private:
  void run();
  void rebuild(std::vector<fs::path> files, std::vector<ShaderLibrary::ProgramId> programs,
               std::chrono::steady_clock::time_point editTime);
  void snapshot();

  ShaderLibrary& lib_;
  std::vector<fs::path> dirs_;
  Timing timing_;
  std::unique_ptr<class DirWatcher> watcher_;
  int wakeFd_ = -1;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> reloadAll_{false};
  std::atomic<uint64_t> reloads_{0};
  std::atomic<bool> rebuilding_{false};
  std::mutex mutex_;
  std::deque<ReloadResult> results_;
  std::map<ShaderLibrary::ProgramId, std::vector<std::shared_ptr<const CompiledShader>>> last_;
};

}  // namespace wb::shader
