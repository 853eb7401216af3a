#include "live/reloader.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "live/watcher.h"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/inotify.h>
#include <unistd.h>

#include <algorithm>
#include <set>
#include <thread>

namespace wb::live {

void lowerThreadPriority() {
  const auto tid = static_cast<id_t>(::syscall(SYS_gettid));
  ::setpriority(PRIO_PROCESS, tid, 10);  // best effort: a failure only keeps the normal priority
}

}  // namespace wb::live

namespace wb::live {

namespace {
using TimePoint = std::chrono::steady_clock::time_point;

class SteadyClock : public Reloader::Clock {
 public:
  TimePoint now() const override { return std::chrono::steady_clock::now(); }
  void wait(std::span<pollfd> fds, int timeoutMs) override {
    ::poll(fds.data(), static_cast<nfds_t>(fds.size()), timeoutMs);
  }
};

bool shaderLike(const fs::path& p) {
  if (shader::stageFromPath(p)) return true;
  const auto e = p.extension();
  return e == ".glsl" || e == ".h" || e == ".inc" || e == ".hlsli";
}

std::string describe(const shader::ShaderKey& k) {
  std::string s = k.path.string();
  if (!k.defines.empty()) {
    s += " [";
    for (size_t i = 0; i < k.defines.size(); ++i)
      s += (i ? "," : "") + k.defines[i].name + (k.defines[i].value.empty() ? "" : "=" + k.defines[i].value);
    s += "]";
  }
  return s;
}
}  // namespace

const shader::ShaderLibrary::ProgramBuild* ReloadResult::buildOf(
    shader::ShaderLibrary::ProgramId program) const {
  for (size_t i = 0; i < programs.size(); ++i)
    if (programs[i] == program) return &builds[i];
  for (size_t i = 0; i < unchangedPrograms.size(); ++i)
    if (unchangedPrograms[i] == program) return &unchangedBuilds[i];
  return nullptr;
}

std::string ReloadResult::error() const {
  std::string all;
  for (auto id : failedPrograms) {
    const auto it = programErrors.find(id);
    if (it != programErrors.end()) all += (all.empty() ? "" : "\n") + it->second;
  }
  return all;
}

Reloader::Reloader(shader::ShaderLibrary& lib, std::vector<fs::path> watchDirs)
    : Reloader(lib, std::move(watchDirs), {}) {}

Reloader::Reloader(shader::ShaderLibrary& lib, std::vector<fs::path> watchDirs, Timing timing)
    : lib_(lib), dirs_(std::move(watchDirs)), timing_(std::move(timing)) {
  if (!timing_.clock) timing_.clock = std::make_shared<SteadyClock>();
}

Reloader::~Reloader() {
  stop();
}

void Reloader::start() {
  if (running_) return;
  watcher_ = std::make_unique<DirWatcher>(dirs_);
  wakeFd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  // What the programs are now, taken here and not on the worker: the worker is niced and may first run long
  // after an edit (on lavapipe the first frame keeps every core busy); a snapshot taken then would hold the
  // edit, and its reload would report nothing recompiled.
  snapshot();
  running_ = true;
  // The compile runs at the render loop's priority: an edit goes first (the loop yields to it, see
  // render/hot_reload.h), and a lowered priority would starve it behind busy programs in the same session.
  thread_ = std::thread([this] { run(); });
}

void Reloader::stop() {
  if (!running_.exchange(false)) return;
  const uint64_t one = 1;
  [[maybe_unused]] auto n = ::write(wakeFd_, &one, sizeof one);
  if (thread_.joinable()) thread_.join();
  ::close(wakeFd_);
  wakeFd_ = -1;
  watcher_.reset();
}

void Reloader::requestReloadAll() {
  const auto all = lib_.programs();
  noteChange({all.begin(), all.end()});
  reloadAll_ = true;
  if (wakeFd_ >= 0) {
    const uint64_t one = 1;
    [[maybe_unused]] auto n = ::write(wakeFd_, &one, sizeof one);
  }
}

std::optional<ReloadResult> Reloader::waitResult(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  if (!resultReady_.wait_for(lock, timeout, [&] { return !results_.empty(); })) return std::nullopt;
  ReloadResult r = std::move(results_.front());
  results_.pop_front();
  return r;
}

std::optional<ReloadResult> Reloader::poll() {
  std::lock_guard lock(mutex_);
  if (results_.empty()) return std::nullopt;
  ReloadResult r = std::move(results_.front());
  results_.pop_front();
  return r;
}

void Reloader::snapshot() {
  for (auto id : lib_.programs()) {
    try {
      last_[id] = lib_.buildProgram(id).stages;
    } catch (const shader::CompileError&) {
    }
  }
}

bool Reloader::eventsWaiting() const {
  if (!watcher_) return false;  // not started
  pollfd fd{watcher_->fd(), POLLIN, 0};
  return ::poll(&fd, 1, 0) > 0 && (fd.revents & POLLIN);
}

bool Reloader::newerChange() const {
  if (rebuilding_ || changesPending_) return true;
  {
    std::lock_guard lock(mutex_);
    if (!results_.empty()) return true;
  }
  return eventsWaiting();  // written already, not yet read by the worker (a busy machine delays it)
}

void Reloader::noteQueuedChanges(std::chrono::milliseconds cap) const {
  const auto deadline = std::chrono::steady_clock::now() + cap;
  while ((eventsWaiting() || absorbing_) && running_ && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

uint64_t Reloader::lastChange(shader::ShaderLibrary::ProgramId program) const {
  std::lock_guard lock(mutex_);
  const auto it = lastChange_.find(program);
  return it == lastChange_.end() ? 0 : it->second;
}

void Reloader::noteChange(const std::set<shader::ShaderLibrary::ProgramId>& programs) {
  if (programs.empty()) return;
  std::lock_guard lock(mutex_);
  ++sequence_;
  for (auto id : programs) lastChange_[id] = sequence_;
}

std::set<shader::ShaderLibrary::ProgramId> Reloader::programsFor(const fs::path& file) const {
  const auto deps = lib_.programsDependingOn(file);
  std::set<shader::ShaderLibrary::ProgramId> programs(deps.begin(), deps.end());
  if (shaderLike(file))
    for (auto id : lib_.programs())
      if (lib_.programOk(id) == false) programs.insert(id);
  return programs;
}

void Reloader::rebuild(const std::vector<fs::path>& files,
                       const std::vector<shader::ShaderLibrary::ProgramId>& programs, TimePoint editTime,
                       bool force) {
  const auto t0 = timing_.clock->now();
  rebuildStart_ = t0.time_since_epoch().count();
  rebuilding_ = true;
  lib_.invalidateFiles(files);
  ReloadResult r;
  r.filesChanged = files;
  r.editTime = editTime;
  r.forced = force;
  {
    std::lock_guard lock(mutex_);
    r.sequence = sequence_;
  }
  std::set<std::string> recompiled;
  std::map<shader::ShaderLibrary::ProgramId, std::vector<std::shared_ptr<const shader::CompiledShader>>> next;
  for (auto id : programs) {
    try {
      auto b = lib_.buildProgram(id);
      const auto& prev = last_[id];
      bool same = prev.size() == b.stages.size();
      for (size_t i = 0; i < b.stages.size(); ++i) {
        const bool stageSame = i < prev.size() && prev[i]->spirv == b.stages[i]->spirv;
        if (!stageSame) recompiled.insert(describe(b.stages[i]->key));
        same = same && stageSame;
      }
      next[id] = b.stages;
      if (same && !force) {
        r.unchangedPrograms.push_back(id);
        r.unchangedBuilds.push_back(std::move(b));
        continue;
      }
      r.programs.push_back(id);
      r.builds.push_back(std::move(b));
    } catch (const shader::CompileError& e) {
      r.ok = false;
      r.failedPrograms.push_back(id);
      r.programErrors[id] = lib_.programName(id) + ":\n" + e.what();
    }
  }
  for (auto& [id, stages] : next) last_[id] = std::move(stages);
  r.stagesRecompiled.assign(recompiled.begin(), recompiled.end());
  r.compileMs = std::chrono::duration<double, std::milli>(timing_.clock->now() - t0).count();
  ++reloads_;
  std::lock_guard lock(mutex_);
  results_.push_back(std::move(r));
  rebuilding_ = false;
  resultReady_.notify_all();
}

void Reloader::run() {
  std::set<fs::path> pending;
  std::set<fs::path> writing;  // modified but not yet closed
  bool overflow = false;
  TimePoint first{}, last{};
  Clock& clock = *timing_.clock;
  while (running_) {
    int timeoutMs = -1;
    if (!pending.empty() || overflow) {
      const auto since = clock.now() - last;
      const auto wait = timing_.quiet - std::chrono::duration_cast<std::chrono::milliseconds>(since);
      timeoutMs = std::max<int>(1, static_cast<int>(wait.count()));
    }
    pollfd fds[2] = {{watcher_->fd(), POLLIN, 0}, {wakeFd_, POLLIN, 0}};
    clock.wait(fds, timeoutMs);
    if (!running_) break;
    if (fds[1].revents & POLLIN) {
      uint64_t v;
      [[maybe_unused]] auto n = ::read(wakeFd_, &v, sizeof v);
    }
    if (reloadAll_.exchange(false)) rebuild({}, lib_.programs(), clock.now(), true);
    // Folds newly read events into the burst; false when there were none.
    auto absorb = [&](const std::vector<DirWatcher::Event>& events) {
      for (const auto& e : events) {
        const auto now = clock.now();
        if (pending.empty() && !overflow) first = now;
        last = now;
        if (e.overflow()) {
          overflow = true;
          const auto all = lib_.programs();
          noteChange({all.begin(), all.end()});
          continue;
        }
        if (e.isDir()) continue;
        // A file just created or modified is being written until its IN_CLOSE_WRITE (a writer descheduled
        // between open() and write() must not get its empty file compiled).
        if (e.mask & (IN_MODIFY | IN_CREATE)) writing.insert(e.path);
        if (e.mask & (IN_CLOSE_WRITE | IN_DELETE | IN_MOVED_FROM)) writing.erase(e.path);
        pending.insert(e.path);
        // Builds of the programs it touches that are in flight are outdated from now on.
        noteChange(programsFor(e.path));
      }
      return !events.empty();
    };
    // Flagged before the read: between taking the events from the kernel and folding them in, neither
    // eventsWaiting() nor `pending` shows them to newerChange().
    if (fds[0].revents & POLLIN) changesPending_ = true;
    absorbing_ = true;
    absorb(watcher_->read());
    absorbing_ = false;
    changesPending_ = !pending.empty() || overflow;
    if (pending.empty() && !overflow) continue;
    const auto quietFor = clock.now() - last;
    if (quietFor < timing_.quiet) continue;
    if (!writing.empty() && quietFor < timing_.writeGrace) continue;  // never compile a half-written file
    // Map files to programs.
    std::set<shader::ShaderLibrary::ProgramId> programs;
    std::vector<fs::path> files;
    bool missingDependency = false;
    for (const auto& p : pending) {
      const auto deps = lib_.programsDependingOn(p);
      if (deps.empty() && !shaderLike(p)) continue;
      std::error_code ec;
      if (!deps.empty() && !fs::exists(p, ec)) missingDependency = true;
      const auto touched = programsFor(p);
      programs.insert(touched.begin(), touched.end());
      files.push_back(p);
    }
    if (missingDependency && quietFor < timing_.recreateGrace) continue;  // delete + recreate
    // What the checks above saw on disk may be newer than the events read so far (a file recreated and
    // written just after the read, seen by exists()): the kernel queued its events before that, so read
    // again, and if there are any, wait for quiet again -- compiling now would reload this save a second time
    // once they come.
    if (absorb(watcher_->read())) continue;
    if (overflow)
      for (auto id : lib_.programs()) programs.insert(id);
    pending.clear();
    writing.clear();
    overflow = false;
    if (programs.empty()) {
      changesPending_ = false;
      continue;
    }
    rebuilding_ = true;  // before the flag below drops: newerChange() stays true throughout
    changesPending_ = false;
    rebuild(files, {programs.begin(), programs.end()}, first, false);
  }
}

}  // namespace wb::live
