// Hot reload: a worker thread watches the shader directories (inotify on directories), coalesces bursts of
// events (a short quiet period, and never while a file is still being written), maps changed files to
// programs through the include graph, rebuilds them off the caller's thread and publishes the results.
#pragma once
#include "shader/library.h"

#include <poll.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <thread>

namespace wb::live {

namespace fs = std::filesystem;

// Lowers the calling thread's scheduling priority (nice +10, Linux threads have their own): work that must
// not compete with the frames (a warm-up device made ahead of the first edit) takes the CPU only when the
// render loop and the driver's threads leave it. It cannot be undone (raising a priority needs privileges).
void lowerThreadPriority();

struct ReloadResult {
  std::vector<fs::path> filesChanged;
  std::vector<std::string> stagesRecompiled;  // stage file paths (+ " [K=V,...]") whose SPIR-V changed
  std::vector<shader::ShaderLibrary::ProgramId> programs;  // rebuilt successfully, parallel to builds
  std::vector<shader::ShaderLibrary::ProgramBuild> builds;
  std::vector<shader::ShaderLibrary::ProgramId> failedPrograms;  // keep their old pipelines
  // Built with the same SPIR-V as their last compile here (a save that changed nothing the compiler keeps,
  // such as a touch or a comment), parallel to unchangedBuilds.
  std::vector<shader::ShaderLibrary::ProgramId> unchangedPrograms;
  std::vector<shader::ShaderLibrary::ProgramBuild> unchangedBuilds;
  double compileMs = 0;  // wall time of the rebuild
  bool ok = true;
  // Each failed program's own lines ("name:" then its file:line: severity: messages), keyed like
  // failedPrograms.
  std::map<shader::ShaderLibrary::ProgramId, std::string> programErrors;
  // Every failure's lines, in failedPrograms order.
  std::string error() const;
  std::chrono::steady_clock::time_point editTime;  // when the first change of the burst was seen
  // The change sequence when the compile began: a program with Reloader::lastChange() above it changed again
  // since (a newer save), and whatever is built from this result for it is outdated.
  uint64_t sequence = 0;
  bool forced = false;  // a reload of everything (requestReloadAll): every program is rebuilt
  // The build of `program` in this result (changed or unchanged), or nullptr (failed, or not compiled).
  const shader::ShaderLibrary::ProgramBuild* buildOf(shader::ShaderLibrary::ProgramId program) const;
};

class Reloader {
 public:
  // The worker's time source: when events came, how long a burst has been quiet, the times a result reports,
  // and how the worker waits for events. The default is std::chrono::steady_clock with poll()'s timeout; a
  // test passes a clock that moves only when told and wakes the worker when it does.
  class Clock {
   public:
    virtual ~Clock() = default;
    virtual std::chrono::steady_clock::time_point now() const = 0;
    // Waits as ::poll(fds, timeoutMs) does (-1: until an fd is readable) and fills the fds' revents. The
    // timeout is in this clock's time: a clock that does not pass by itself wakes the worker when it moves.
    virtual void wait(std::span<pollfd> fds, int timeoutMs) = 0;
  };
  struct Timing {
    std::chrono::milliseconds quiet{5};            // no events for this long = the burst is over
    std::chrono::milliseconds writeGrace{1000};    // wait this long for a file still open for writing
    std::chrono::milliseconds recreateGrace{300};  // wait this long for a deleted dependency to reappear
    std::shared_ptr<Clock> clock;                  // null: std::chrono::steady_clock
  };
  Reloader(shader::ShaderLibrary& lib, std::vector<fs::path> watchDirs);
  Reloader(shader::ShaderLibrary& lib, std::vector<fs::path> watchDirs, Timing timing);
  ~Reloader();
  Reloader(const Reloader&) = delete;
  Reloader& operator=(const Reloader&) = delete;

  // Adds the watches and records the programs' current stages (synchronously), then starts the worker.
  void start();
  void stop();
  std::optional<ReloadResult> poll();  // non-blocking; one result per coalesced change
  // poll(), waiting up to `timeout` for a result (a consumer thread takes each one as soon as it is there).
  std::optional<ReloadResult> waitResult(std::chrono::milliseconds timeout);
  void requestReloadAll();
  uint64_t reloadCount() const { return reloads_; }
  bool rebuilding() const { return rebuilding_; }  // a coalesced change is being compiled right now
  // A change newer than the last published result may exist: events not yet read, files changed and not yet
  // compiled, a compile in progress, or results not yet taken by poll(). It may still come to nothing (a file
  // no program uses): a consumer drops a build for an older result only once a newer result is there. Between
  // start() and stop().
  bool newerChange() const;
  // The change sequence at the last change seen to one of `program`'s files (an event read from the watcher,
  // before its burst is compiled), 0 if none since start(). Thread-safe.
  uint64_t lastChange(shader::ShaderLibrary::ProgramId program) const;
  // Waits (at most `cap`) until the worker has read every event the kernel has queued so far, so that
  // lastChange() counts every save written before this call.
  void noteQueuedChanges(std::chrono::milliseconds cap) const;
  // When the compile in progress began (meaningful while rebuilding()).
  std::chrono::steady_clock::time_point rebuildStart() const {
    return std::chrono::steady_clock::time_point(std::chrono::steady_clock::duration(rebuildStart_.load()));
  }

 private:
  void run();
  // Compiles `programs` and publishes the result. A change seen while it compiles is compiled by the next
  // burst; what is built from this result for the programs it touches is dropped then (lastChange()).
  // `force` reports every program that compiled as changed.
  void rebuild(const std::vector<fs::path>& files,
               const std::vector<shader::ShaderLibrary::ProgramId>& programs,
               std::chrono::steady_clock::time_point editTime, bool force);
  // The programs a changed file may rebuild: those that include it, and for a shader-like file every program
  // that failed last time (it may be waiting for exactly this file).
  std::set<shader::ShaderLibrary::ProgramId> programsFor(const fs::path& file) const;
  // A change to these programs is seen now.
  void noteChange(const std::set<shader::ShaderLibrary::ProgramId>& programs);
  bool eventsWaiting() const;  // the watcher has unread events
  void snapshot();

  shader::ShaderLibrary& lib_;
  std::vector<fs::path> dirs_;
  Timing timing_;
  std::unique_ptr<class DirWatcher> watcher_;
  int wakeFd_ = -1;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::atomic<bool> reloadAll_{false};
  std::atomic<uint64_t> reloads_{0};
  std::atomic<bool> rebuilding_{false};
  std::atomic<bool> changesPending_{false};
  std::atomic<bool> absorbing_{false};  // the worker is reading and noting events
  std::atomic<std::chrono::steady_clock::rep> rebuildStart_{0};
  mutable std::mutex mutex_;
  std::deque<ReloadResult> results_;
  std::condition_variable resultReady_;
  std::map<shader::ShaderLibrary::ProgramId, std::vector<std::shared_ptr<const shader::CompiledShader>>>
      last_;
  uint64_t sequence_ = 0;                                            // guarded by mutex_
  std::map<shader::ShaderLibrary::ProgramId, uint64_t> lastChange_;  // guarded by mutex_
};

}  // namespace wb::live
