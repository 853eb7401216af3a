#include "render/hot_reload.h"

#include <algorithm>
#include <map>
#include <set>
#include <thread>

namespace wb::render {
namespace {

double msBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

HotReload::HotReload(shader::ShaderLibrary& library, std::vector<std::filesystem::path> watchDirs)
    : library_(library), reloader_(library, std::move(watchDirs)) {}

HotReload::~HotReload() {
  stop();
}

void HotReload::addTarget(shader::ShaderLibrary::ProgramId program, Target target) {
  std::lock_guard lock(mutex_);
  targets_[program] = std::move(target);
}

HotReload::Warmup& HotReload::warmupFor(const Renderer& renderer) {
  std::lock_guard lock(mutex_);
  auto& w = warmups_[&renderer];
  if (!w) {
    w = std::make_unique<Warmup>();
    w->enabled = renderer.context().policy().jitWarmup;
  }
  return *w;
}

void HotReload::compileAhead(Renderer& renderer) {
  Warmup& warmup = warmupFor(renderer);
  if (!warmup.enabled) return;
  const auto programs = renderer.programs();
  for (size_t i = 0; i < programs.size(); ++i) {
    const auto build = library_.buildProgram(programs[i].id);
    renderer.installPipeline(programs[i].id, buildWithWarmup(renderer, warmup, i, programs[i].id, build));
  }
}

void HotReload::addRenderer(Renderer& renderer) {
  Warmup* warmup = &warmupFor(renderer);
  const auto programs = renderer.programs();
  for (size_t i = 0; i < programs.size(); ++i) {
    const auto id = programs[i].id;
    {
      std::lock_guard lock(mutex_);
      if (targets_.count(id)) continue;
    }
    // The build the renderer's pipeline was made from (the library's cache holds it): the A/B comparison's
    // and a revert's old side of the first edit.
    try {
      auto build = library_.buildProgram(id);
      std::lock_guard lock(mutex_);
      installedBuilds_.emplace(id, std::move(build));
    } catch (const std::exception&) {
      // Not buildable now (a broken file saved since): the first edit has no old side to compare.
    }
    addTarget(id, {programs[i].name,
                   [this, &renderer, warmup, i, id](const shader::ShaderLibrary::ProgramBuild& b) {
                     return buildWithWarmup(renderer, *warmup, i, id, b);
                   },
                   [&renderer, id](std::unique_ptr<vk::BuiltPipeline> p) {
                     renderer.installPipeline(id, std::move(p));
                   },
                   &renderer, i,
                   [&renderer, id](std::unique_ptr<vk::BuiltPipeline> p) {
                     return renderer.exchangePipeline(id, std::move(p));
                   }});
  }
  if (warmup->enabled) {
    const auto options = library_.options();
    warmup->slot.makeAhead([&renderer, options] { return std::make_unique<JitWarmup>(renderer, options); });
  }
}

std::unique_ptr<vk::BuiltPipeline> HotReload::buildWithWarmup(
    Renderer& renderer, Warmup& warmup, size_t programIndex, shader::ShaderLibrary::ProgramId program,
    const shader::ShaderLibrary::ProgramBuild& build) {
  if (!warmup.enabled) return renderer.buildPipeline(program, build);
  // The driver's compile on the warm-up device runs beside this device's pipeline creation; the probe comes
  // first so that the warm-up can number its groups like the pipeline built here.
  const auto counter = probeGroupCounter(renderer.context(), build);
  std::vector<uint8_t> warmedHandles;  // empty: no warm-up ran, or not a ray tracing pipeline
  const auto options = library_.options();
  auto built = buildBesideWarmup(
      warmup.enabled, [&] { return renderer.buildPipeline(program, build); },
      [&] {
        auto make = [&] { return std::make_unique<JitWarmup>(renderer, options); };
        if (auto* w = warmup.slot.warmOrRenew(make, [&](JitWarmup& x) {
              return x.warm(renderer, programIndex, build, counter.value_or(0));
            }))
          warmedHandles = w->groupHandles();
      });
  if (!warmedHandles.empty() && built->rayTracing && warmedHandles != built->rayTracing->sbt().groupHandles())
    ++warmup.mismatches;
  return built;
}

HotReload::WarmupStats HotReload::jitWarmup(const Renderer& renderer) const {
  const Warmup* w = nullptr;
  {
    std::lock_guard lock(mutex_);
    auto it = warmups_.find(&renderer);
    if (it == warmups_.end()) return {};
    w = it->second.get();  // entries live as long as this object
  }
  WarmupStats s;
  s.enabled = w->enabled;
  s.present = w->slot.present();
  s.warmups = w->slot.warmups();
  s.mismatches = w->mismatches;
  return s;
}

void HotReload::start() {
  if (running_) return;
  reloader_.start();
  running_ = true;
  // Pipeline builds run at the render loop's priority: an edit goes first (the loop yields to it).
  thread_ = std::thread([this] { run(); });
}

void HotReload::stop() {
  if (!running_) return;
  running_ = false;
  if (thread_.joinable()) thread_.join();
  reloader_.stop();
}

void HotReload::reloadAll() {
  manualRequest_ = true;
  reloader_.requestReloadAll();
}

void HotReload::run() {
  // Programs of results dropped for a newer save: built with the next result, from the library's newest
  // content (cached: nothing compiles twice).
  std::set<shader::ShaderLibrary::ProgramId> carried;
  std::set<std::string> carriedFiles;
  std::optional<shader::ReloadResult> next;  // a newer result, taken while the older one was handled
  // A newer change is seen: its result, once there, or nothing when the change yields none (a file no program
  // uses) and the result in hand stands.
  auto newerResult = [&]() -> std::optional<shader::ReloadResult> {
    while (running_ && reloader_.newerChange())
      if (auto r = reloader_.waitResult(std::chrono::milliseconds(5))) return r;
    return std::nullopt;
  };
  while (running_) {
    std::optional<shader::ReloadResult> result = std::move(next);
    next.reset();
    if (!result) result = reloader_.waitResult(std::chrono::milliseconds(50));  // running_ checked between
    if (!result) continue;
    // With auto-reload off, file changes are noticed (the UI shows them) but only a manual reload applies.
    if (!autoReload_ && !manualRequest_.exchange(false)) continue;
    manualRequest_ = false;
    prepareStart_ = std::chrono::steady_clock::now().time_since_epoch().count();
    preparing_ = true;
    for (const auto& f : result->filesChanged) carriedFiles.insert(f.string());
    // A newer save is already there: only the newest content is built.
    auto supersede = [&] {
      carried.insert(result->programs.begin(), result->programs.end());
      carried.insert(result->failedPrograms.begin(), result->failedPrograms.end());
      ++superseded_;
      preparing_ = false;
    };
    if ((next = newerResult())) {
      supersede();
      continue;
    }
    for (auto id : result->programs) carried.erase(id);
    for (auto id : result->failedPrograms) carried.erase(id);
    // An unchanged program stays carried: its content may be the dropped build's, never installed.
    std::erase_if(result->unchangedPrograms, [&](auto id) { return carried.count(id) > 0; });
    for (auto id : carried) {
      try {
        result->builds.push_back(library_.buildProgram(id));
        result->programs.push_back(id);
      } catch (const shader::CompileError& e) {
        result->ok = false;
        result->failedPrograms.push_back(id);
        result->programErrors[id] = library_.programName(id) + ":\n" + e.what();
      }
    }
    Pending p;
    p.editTime = result->editTime;
    p.event.editSeen = result->editTime;
    p.event.when = std::chrono::system_clock::now();
    p.event.filesChanged.assign(carriedFiles.begin(), carriedFiles.end());
    p.event.stagesRecompiled = result->stagesRecompiled;
    p.event.compileMs = result->compileMs;
    p.event.ok = result->ok;
    p.event.error = result->error();
    auto t0 = std::chrono::steady_clock::now();
    std::map<shader::ShaderLibrary::ProgramId, std::string> pipelineErrors;
    bool dropped = false;
    for (size_t i = 0; i < result->programs.size() && !dropped; ++i) {
      Target target;
      {
        std::lock_guard lock(mutex_);
        auto it = targets_.find(result->programs[i]);
        if (it == targets_.end()) continue;
        target = it->second;
      }
      try {
        p.built.emplace_back(result->programs[i], target.build(result->builds[i]));
        p.builds.push_back(result->builds[i]);
        p.event.pipelinesRebuilt.push_back(target.name);
        const vk::RtLibraryStats s = p.built.back().second->libraryStats();
        p.event.libraries.librariesCompiled += s.librariesCompiled;
        p.event.libraries.librariesReused += s.librariesReused;
        p.event.libraries.libraryMs += s.libraryMs;
        p.event.libraries.linkMs += s.linkMs;
      } catch (const std::exception& e) {
        // The program compiled but its pipeline did not build (or uses a binding the renderer does not fill:
        // a CompileError at its declaration): the last good pipeline stays, and the error is current (banner,
        // Shaders panel) until a later build of this program succeeds.
        const bool compileError = dynamic_cast<const shader::CompileError*>(&e) != nullptr;
        const std::string message =
            target.name + (compileError ? ": " : ": pipeline creation failed: ") + e.what();
        p.event.ok = false;
        p.event.error += (p.event.error.empty() ? "" : "\n") + message;
        pipelineErrors[result->programs[i]] = message;
      }
      dropped = (next = newerResult()).has_value();  // the build just made is dropped for a newer result
    }
    if (dropped) {
      supersede();
      continue;
    }
    carried.clear();
    carriedFiles.clear();
    p.event.pipelineMs = msBetween(t0, std::chrono::steady_clock::now());
    {
      std::lock_guard lock(mutex_);
      for (const auto& [id, message] : result->programErrors) errors_[id] = message;
      // Every program that compiled is rid of its compile error, built here or not (a program without a
      // target, such as a variant no renderer uses now, would otherwise keep it forever).
      for (auto id : result->programs) {
        errors_.erase(id);
        pipelineFailed_.erase(id);
      }
      for (const auto& [id, message] : pipelineErrors) {
        errors_[id] = message;
        pipelineFailed_.insert(id);
      }
      // The same SPIR-V as the pipeline in use (or as the one that failed to build): nothing to do, except
      // that a compile error fixed back to the working content is no longer current.
      for (auto id : result->unchangedPrograms)
        if (!pipelineFailed_.count(id)) errors_.erase(id);
      pending_.push_back(std::move(p));
      preparing_ = false;
    }
    if (onReady_) onReady_();
  }
}

HotReload::Status HotReload::status() const {
  Status s;
  s.superseded = superseded_;
  const auto now = std::chrono::steady_clock::now();
  auto since = [&](std::chrono::steady_clock::rep t) {
    return msBetween(std::chrono::steady_clock::time_point(std::chrono::steady_clock::duration(t)), now);
  };
  if (reloader_.rebuilding()) {
    s.stage = Status::Stage::Compiling;
    s.elapsedMs = since(reloader_.rebuildStart().time_since_epoch().count());
  } else if (preparing_) {
    s.stage = Status::Stage::BuildingPipelines;
    s.elapsedMs = since(prepareStart_);
  } else {
    std::lock_guard lock(mutex_);
    if (!pending_.empty()) {
      s.stage = Status::Stage::Installing;
      s.elapsedMs = msBetween(pending_.front().editTime, now);
    }
  }
  return s;
}

const char* HotReload::stageName(Status::Stage s) {
  switch (s) {
    case Status::Stage::Compiling:
      return "compiling shaders";
    case Status::Stage::BuildingPipelines:
      return "building pipelines";
    case Status::Stage::Installing:
      return "installing";
    case Status::Stage::Idle:
      break;
  }
  return "idle";
}

std::optional<ReloadEvent> HotReload::poll() {
  std::optional<Pending> p;
  {
    std::lock_guard lock(mutex_);
    if (pending_.empty()) return std::nullopt;
    p = std::move(pending_.front());
    pending_.pop_front();
  }
  lastInstalled_.clear();
  for (size_t i = 0; i < p->built.size(); ++i) {
    auto& [id, built] = p->built[i];
    Target target;
    std::optional<shader::ShaderLibrary::ProgramBuild> before;
    {
      std::lock_guard lock(mutex_);
      target = targets_.at(id);
      auto it = installedBuilds_.find(id);
      if (it != installedBuilds_.end()) before = it->second;
      installedBuilds_[id] = p->builds[i];
    }
    std::shared_ptr<vk::BuiltPipeline> old;
    if (target.exchange) {
      old = target.exchange(std::move(built));
    } else {
      target.install(std::move(built));
    }
    if (before && old && target.renderer)
      lastInstalled_.push_back(
          {id, target.name, target.renderer, target.programIndex, std::move(old), *before, p->builds[i]});
  }
  const auto now = std::chrono::steady_clock::now();
  p->event.editToNewPipelineMs = msBetween(p->editTime, now);
  if (p->built.empty()) p->event.frames = frameTimeline_.stats(p->editTime, false);
  std::lock_guard lock(mutex_);
  history_.push_back(p->event);
  awaitingFrame_ = p->built.empty() ? std::nullopt : std::optional(p->editTime);
  return p->event;
}

void HotReload::frameFinished(std::optional<std::chrono::steady_clock::time_point> frameBegin) {
  const auto now = std::chrono::steady_clock::now();
  const auto begin = frameBegin ? *frameBegin : lastFrameEnd_.value_or(now);
  lastFrameEnd_ = now;
  frameTimeline_.add(begin, now);
  std::lock_guard lock(mutex_);
  if (!awaitingFrame_ || history_.empty()) return;
  history_.back().editToFirstFrameMs = msBetween(*awaitingFrame_, now);
  history_.back().frames = frameTimeline_.stats(*awaitingFrame_, true);
  awaitingFrame_.reset();
}

void HotReload::attachAB(std::vector<ReloadAB> ab, double ms) {
  std::lock_guard lock(mutex_);
  if (history_.empty()) return;
  history_.back().ab = std::move(ab);
  history_.back().abMs = ms;
}

void HotReload::revert(const std::vector<InstalledProgram>& installed) {
  for (const auto& ip : installed) {
    if (!ip.renderer || !ip.oldPipeline) continue;
    ip.renderer->exchangePipeline(ip.program, ip.oldPipeline);
    std::lock_guard lock(mutex_);
    installedBuilds_[ip.program] = ip.before;
  }
  std::lock_guard lock(mutex_);
  if (!history_.empty()) history_.back().reverted = true;
}

bool HotReload::busy() const {
  if (compiling() || reloader_.newerChange()) return true;
  std::lock_guard lock(mutex_);
  return !pending_.empty();
}

std::optional<ReloadEvent> HotReload::lastEvent() const {
  std::lock_guard lock(mutex_);
  if (history_.empty()) return std::nullopt;
  return history_.back();
}

std::vector<ReloadEvent> HotReload::history() const {
  std::lock_guard lock(mutex_);
  return history_;
}

std::string HotReload::currentError() const {
  std::lock_guard lock(mutex_);
  std::string all;
  std::set<std::string> shown;  // programs of the same name and file fail alike: each message once
  for (const auto& [id, e] : errors_)
    if (shown.insert(e).second) all += (all.empty() ? "" : "\n") + e;
  return all;
}

}  // namespace wb::render
