#include "live/hot_reload.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <thread>

namespace wb::live {
namespace {

double msBetween(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// A pipeline whose trial frame never finished, as the user reads it: the stages whose SPIR-V differs from the
// installed pipeline's (the edit), the limit, and what happens.
std::string describeHang(const shader::ShaderLibrary::ProgramBuild& build,
                         const shader::ShaderLibrary::ProgramBuild& installed, double limitSeconds,
                         double cpuSeconds) {
  std::string stages;
  for (size_t i = 0; i < build.stages.size(); ++i) {
    const auto& s = build.stages[i];
    const bool same =
        i < installed.stages.size() && installed.stages[i] && installed.stages[i]->spirv == s->spirv;
    if (!same) stages += (stages.empty() ? "" : ", ") + s->key.path.string();
  }
  char limit[96];
  if (cpuSeconds >= 0)
    std::snprintf(limit, sizeof limit, "%.1f s (its device's threads ran %.1f s of CPU)", limitSeconds,
                  cpuSeconds);
  else
    std::snprintf(limit, sizeof limit, "%.1f s", limitSeconds);
  return "the new " + (stages.empty() ? std::string("pipeline") : stages) + " did not finish a " +
         std::to_string(kTrialSize) + "x" + std::to_string(kTrialSize) + " trial frame in " + limit +
         ": an endless loop? The edit is refused and the last good pipeline stays (the trial ran on a second "
         "device, which the workbench leaves behind)";
}

bool sameSpirv(const shader::ShaderLibrary::ProgramBuild& a, const shader::ShaderLibrary::ProgramBuild& b) {
  if (a.stages.size() != b.stages.size()) return false;
  for (size_t i = 0; i < a.stages.size(); ++i)
    if (!a.stages[i] || !b.stages[i] || a.stages[i]->spirv != b.stages[i]->spirv) return false;
  return true;
}

}  // namespace

HotReload::HotReload(shader::ShaderLibrary& library, std::vector<std::filesystem::path> watchDirs)
    : library_(library), reloader_(library, std::move(watchDirs)) {}

HotReload::~HotReload() {
  stop();
}

std::vector<HotReload::Entry*> HotReload::entries() const {
  std::lock_guard lock(mutex_);
  std::vector<Entry*> out;
  for (const auto& e : entries_) out.push_back(e.get());
  return out;
}

void HotReload::addPass(render::ReloadTarget& pass) {
  std::lock_guard lock(mutex_);
  for (const auto& e : entries_)
    if (e->pass == &pass) return;
  auto e = std::make_unique<Entry>();
  e->pass = &pass;
  entries_.push_back(std::move(e));
}

HotReload::Warmup* HotReload::warmupFor(const render::Renderer& renderer) {
  std::lock_guard lock(mutex_);
  auto& w = warmups_[&renderer];
  if (!w) {
    w = std::make_unique<Warmup>();
    const auto& policy = renderer.context().policy();
    w->enabled = policy.jitWarmup || policy.trialRuns;
    w->compileAhead = policy.jitWarmup;
  }
  return w.get();
}

void HotReload::compileAhead(render::Renderer& renderer) {
  Warmup* warmup = warmupFor(renderer);
  if (!warmup->enabled) return;
  const auto passes = renderer.passes();
  for (size_t i = 0; i < passes.size(); ++i) {
    const Entry entry{passes[i], &renderer, i, warmup};
    const auto program = passes[i]->program();
    passes[i]->install(buildWithWarmup(entry, program, library_.buildProgram(program)));
  }
}

render::RendererHooks HotReload::sessionHooks() {
  return {[this](render::Renderer& r) { addRenderer(r); }, [this](render::Renderer& r) { compileAhead(r); }};
}

void HotReload::addRenderer(render::Renderer& renderer) {
  Warmup* warmup = warmupFor(renderer);
  const auto passes = renderer.passes();
  {
    std::lock_guard lock(mutex_);
    for (size_t i = 0; i < passes.size(); ++i) {
      const bool known =
          std::any_of(entries_.begin(), entries_.end(), [&](const auto& e) { return e->pass == passes[i]; });
      if (known) continue;
      entries_.push_back(std::make_unique<Entry>(Entry{passes[i], &renderer, i, warmup}));
    }
  }
  if (warmup->enabled) {
    const auto options = library_.options();
    warmup->slot.makeAhead([&renderer, options] { return std::make_unique<JitWarmup>(renderer, options); });
  }
}

render::PassPipeline HotReload::buildWithWarmup(const Entry& entry, shader::ShaderLibrary::ProgramId program,
                                                const shader::ShaderLibrary::ProgramBuild& build) {
  Warmup* warmup = entry.warmup;
  if (!warmup || !warmup->enabled) return entry.pass->buildPipeline(program, build);
  render::Renderer& renderer = *entry.owner;
  // The driver's compile on the warm-up device runs beside this device's pipeline creation; the probe comes
  // first so that the warm-up can number its groups like the pipeline built here.
  const auto counter =
      warmup->compileAhead ? probeGroupCounter(renderer.context(), build) : std::optional<uint32_t>();
  std::vector<uint8_t> warmedHandles;  // empty: no warm-up ran, or not a ray tracing pipeline
  const auto options = library_.options();
  bool failed = false;
  WarmOutcome outcome = WarmOutcome::Warmed;
  double limit = 0, hangCpu = -1;
  auto built = buildBesideWarmup([&] { return entry.pass->buildPipeline(program, build); },
                                 [&] {
                                   auto make = [&] { return std::make_unique<JitWarmup>(renderer, options); };
                                   const auto [w, o] = warmup->slot.warmOrRenew(make, [&](JitWarmup& x) {
                                     const WarmOutcome r = x.warm(renderer, entry.passIndex, build, counter,
                                                                  warmup->compileAhead);
                                     limit = x.trialLimitSeconds();
                                     hangCpu = x.hangCpuSeconds();
                                     return r;
                                   });
                                   outcome = o;
                                   if (w) warmedHandles = w->groupHandles();
                                 },
                                 failed);
  if (failed) ++warmup->failures;
  if (outcome == WarmOutcome::Hung) {
    // A new warm-up device for the next reload, made now off the loop.
    warmup->slot.makeAhead([&renderer, options] { return std::make_unique<JitWarmup>(renderer, options); });
    throw TrialHang(describeHang(build, entry.pass->installed().build, limit, hangCpu));
  }
  const auto& rt = built.pipeline->rayTracing;
  if (!warmedHandles.empty() && rt && warmedHandles != rt->sbt().groupHandles()) ++warmup->mismatches;
  return built;
}

HotReload::WarmupStats HotReload::jitWarmup(const render::Renderer& renderer) const {
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
  s.failures = w->failures;
  s.hung = w->slot.hung();
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
  while (running_) {
    auto result = reloader_.waitResult(std::chrono::milliseconds(50));  // running_ checked between
    if (!result) continue;
    // With auto-reload off, file changes are noticed (the UI shows them) but only a manual reload applies.
    if (!autoReload_ && !manualRequest_.exchange(false)) continue;
    manualRequest_ = false;
    prepareStart_ = std::chrono::steady_clock::now().time_since_epoch().count();
    preparing_ = true;
    const bool ready = prepare(*result);
    preparing_ = false;
    if (ready && onReady_) onReady_();
  }
}

bool HotReload::prepare(ReloadResult& result) {
  {
    std::lock_guard lock(mutex_);
    for (const auto& f : result.filesChanged) carriedFiles_.insert(f.string());
  }
  // A program changed again since this compile: a newer result is on its way, and what is built from this
  // one for it would be dropped at install. A result outdated for every program it holds is dropped whole
  // (its files are reported with the next event).
  auto outdated = [&](shader::ShaderLibrary::ProgramId id) {
    return reloader_.lastChange(id) > result.sequence;
  };
  bool current = false;
  for (const auto* list : {&result.programs, &result.unchangedPrograms, &result.failedPrograms})
    for (auto id : *list) current = current || !outdated(id);
  if (!current &&
      (!result.programs.empty() || !result.failedPrograms.empty() || !result.unchangedPrograms.empty())) {
    ++superseded_;
    return false;
  }

  Pending p;
  p.sequence = result.sequence;
  p.editTime = result.editTime;
  p.event.editSeen = result.editTime;
  p.event.when = std::chrono::system_clock::now();
  p.event.stagesRecompiled = result.stagesRecompiled;
  p.event.compileMs = result.compileMs;
  p.event.ok = result.ok;
  p.event.error = result.error();
  const auto t0 = std::chrono::steady_clock::now();
  std::map<shader::ShaderLibrary::ProgramId, std::string> pipelineErrors;
  std::set<shader::ShaderLibrary::ProgramId> builtOk;
  for (Entry* e : entries()) {
    const auto program = e->pass->program();
    const auto* build = result.buildOf(program);
    if (!build || outdated(program)) continue;
    // The same SPIR-V as the installed pipeline's (a touch, a comment; or a save back to what is
    // installed): nothing to build, unless a reload of everything was asked for.
    if (!result.forced && sameSpirv(*build, e->pass->installed().build)) continue;
    try {
      Built b{e, buildWithWarmup(*e, program, *build)};
      const vk::RtLibraryStats s = b.pipeline.pipeline->libraryStats();
      p.event.libraries.librariesCompiled += s.librariesCompiled;
      p.event.libraries.librariesReused += s.librariesReused;
      p.event.libraries.libraryMs += s.libraryMs;
      p.event.libraries.linkMs += s.linkMs;
      p.event.pipelinesRebuilt.push_back(e->pass->name());
      p.built.push_back(std::move(b));
      builtOk.insert(program);
    } catch (const std::exception& ex) {
      // The program compiled but its pipeline did not build (or uses a resource the pass does not bind: a
      // shader::CompileError at its declaration): the last good pipeline stays, and the error is current
      // (banner, Shaders panel) until a later build of this program succeeds.
      const bool compileError = dynamic_cast<const shader::CompileError*>(&ex) != nullptr ||
                                dynamic_cast<const TrialHang*>(&ex) != nullptr;
      const std::string message =
          e->pass->name() + (compileError ? ": " : ": pipeline creation failed: ") + ex.what();
      p.event.ok = false;
      p.event.error += (p.event.error.empty() ? "" : "\n") + message;
      pipelineErrors[program] = message;
    }
  }
  p.event.pipelineMs = msBetween(t0, std::chrono::steady_clock::now());
  // Saves written while these were built supersede them: the counters see every one queued by now, and a
  // build they outdate is not offered for install (poll() checks again for later ones).
  reloader_.noteQueuedChanges(std::chrono::milliseconds(1000));
  const size_t builtBefore = p.built.size();
  std::erase_if(p.built, [&](const Built& b) { return outdated(b.pipeline.program); });
  if (builtBefore > 0 && p.built.empty() && p.event.ok) {
    ++superseded_;  // its files stay carried: the newer event reports them
    return false;
  }
  std::lock_guard lock(mutex_);
  p.event.filesChanged.assign(carriedFiles_.begin(), carriedFiles_.end());
  carriedFiles_.clear();
  for (const auto& [id, message] : result.programErrors) errors_[id] = message;
  // Every program that compiled is rid of its compile error, built here or not (a program no pass uses now,
  // such as another variant, would otherwise keep it forever); one whose SPIR-V is unchanged keeps the error
  // of a pipeline that failed to build from that SPIR-V.
  for (auto id : result.programs) {
    errors_.erase(id);
    pipelineFailed_.erase(id);
  }
  for (auto id : result.unchangedPrograms)
    if (!pipelineFailed_.count(id)) errors_.erase(id);
  for (auto id : builtOk) {
    errors_.erase(id);
    pipelineFailed_.erase(id);
  }
  for (const auto& [id, message] : pipelineErrors) {
    errors_[id] = message;
    pipelineFailed_.insert(id);
  }
  pending_.push_back(std::move(p));
  return true;
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
  std::vector<std::string> installed;
  for (auto& b : p->built) {
    // A newer save of this program is being compiled or built: this pipeline is outdated.
    if (reloader_.lastChange(b.pipeline.program) > p->sequence) {
      ++superseded_;
      continue;
    }
    Entry& e = *b.entry;
    render::PassPipeline after = b.pipeline;
    render::PassPipeline before = e.pass->install(std::move(b.pipeline));
    if (!before) continue;  // the pass switched to another program meanwhile
    installed.push_back(e.pass->name());
    if (e.owner)
      lastInstalled_.push_back({e.pass, e.owner, e.passIndex, e.pass->name(), std::move(before), after});
  }
  const bool nothingInstalled = installed.empty() && !p->built.empty();
  p->event.pipelinesRebuilt = installed;
  const auto now = std::chrono::steady_clock::now();
  p->event.editToNewPipelineMs = msBetween(p->editTime, now);
  if (installed.empty()) p->event.frames = frameTimeline_.stats(p->editTime, false);
  std::lock_guard lock(mutex_);
  if (nothingInstalled && p->event.ok) {
    // Every build was superseded: the newer event reports these files.
    for (const auto& f : p->event.filesChanged) carriedFiles_.insert(f);
    return std::nullopt;
  }
  history_.push_back(p->event);
  awaitingFrame_ = installed.empty() ? std::nullopt : std::optional(p->editTime);
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

std::vector<std::filesystem::path> HotReload::revert(const std::vector<InstalledPass>& installed) {
  std::vector<std::filesystem::path> unknown;
  for (const auto& ip : installed) {
    if (!ip.pass || !ip.before) continue;
    ip.pass->install(ip.before);
    for (auto& f : library_.keepSourcesOf(ip.before.build.stages))
      if (std::find(unknown.begin(), unknown.end(), f) == unknown.end()) unknown.push_back(std::move(f));
  }
  std::lock_guard lock(mutex_);
  if (!history_.empty()) history_.back().reverted = true;
  return unknown;
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

}  // namespace wb::live
