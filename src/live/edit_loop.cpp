#include "live/edit_loop.h"

#include <algorithm>
#include <cstdio>

#include "common/paths.h"
#include "common/statistics.h"

namespace wb::live {

EditLoop::EditLoop(render::RenderSession& session, EditLoopOptions options)
    : session_(session), budget_(options.budget), adaptiveBudget_(options.adaptiveBudget) {
  if (options.watchDirs.empty()) options.watchDirs = {shaderDir()};
  hot_ = std::make_unique<HotReload>(session.library(), options.watchDirs);
  // Every renderer's passes, the modes made later too (and those compiled ahead while being made).
  session_.setRendererHooks(hot_->sessionHooks());
  setAB(options.ab);
}

EditLoop::~EditLoop() {
  hot_->stop();
  comparison_.reset();  // its stand-ins render on the session's device
  completed_.clear();   // the old pipelines kept for Revert
  session_.setRendererHooks({});
}

void EditLoop::start(std::function<void()> onReady) {
  if (onReady) hot_->setOnReady(std::move(onReady));
  hot_->start();
}

void EditLoop::setAB(bool on) {
  abOn_ = on;
}

void EditLoop::prepareAB() {
  if (!comparison_) comparison_ = std::make_unique<ABComparison>(session_, budget_);
  comparison_->prepare();
}

void EditLoop::setABBudget(const ABBudget& budget) {
  budget_ = budget;
  if (comparison_) comparison_->setBudget(budget);
}

std::optional<ReloadEvent> EditLoop::beginFrame() {
  auto e = hot_->poll();
  if (!e) return e;
  if (e->pipelinesRebuilt.empty()) {
    completed_.push_back({*e, {}, {}, {}});  // nothing to draw with: a failure keeps the old pipeline
  } else {
    awaitingFirstFrame_ = true;
    if (!abOn_ && comparison_) comparison_->reset();  // its stand-ins no longer match what is installed
  }
  return e;
}

void EditLoop::frameFinished(Clock::time_point frameBegin) {
  hot_->frameFinished(frameBegin);
  // The typical frame leaves out the frames that may have compiled a pipeline (a driver that compiles at the
  // first dispatch does it there): the loop's first frame and the frames of a new pipeline until its image's
  // first frame is done. One of those, seconds long, would otherwise set the hang limit to minutes.
  if (firstFrameDone_ && !awaitingFirstFrame_) {
    frameSeconds_.push_back(std::chrono::duration<double>(Clock::now() - frameBegin).count());
    if (frameSeconds_.size() > 32) frameSeconds_.pop_front();
  }
  firstFrameDone_ = true;
  if (!awaitingFirstFrame_) return;
  const auto last = hot_->lastEvent();
  if (!last || last->editToFirstFrameMs < 0) return;  // the new image's first frame is not done yet
  awaitingFirstFrame_ = false;
  CompletedReload c;
  c.installed = hot_->lastInstalled();
  if (abOn_) {
    const auto t0 = Clock::now();
    if (!comparison_) comparison_ = std::make_unique<ABComparison>(session_, budget_);
    // The comparisons share the allowance: one per rebuilt pass of a session renderer.
    uint32_t comparisons = 0;
    for (const auto& ip : c.installed) comparisons += ip.owner != nullptr;
    c.abPlan = planner_.plan(budget_, adaptiveBudget_ ? last->editToFirstFrameMs : -1.0, comparisons);
    comparison_->setBudget(c.abPlan.budget);
    try {
      c.ab = comparison_->compare(c.installed);
      std::vector<ReloadAB> results;
      for (const auto& o : c.ab) results.push_back(o.result);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      if (!c.ab.empty()) planner_.observe(c.abPlan, ms);
      hot_->attachAB(std::move(results), ms);
    } catch (const std::exception& e) {
      comparison_->reset();
      c.ab.clear();
      c.abError = e.what();
    }
  }
  c.event = *hot_->lastEvent();
  completed_.push_back(std::move(c));
}

std::vector<CompletedReload> EditLoop::takeCompleted() {
  std::vector<CompletedReload> out(std::make_move_iterator(completed_.begin()),
                                   std::make_move_iterator(completed_.end()));
  completed_.clear();
  return out;
}

EditLoop::Clock::time_point EditLoop::restUntil(Clock::time_point frameBegin, Clock::time_point frameEnd,
                                                double ratio) const {
  if (ratio <= 0 || !hot_->compiling()) return frameEnd;
  return frameEnd + std::chrono::duration_cast<Clock::duration>((frameEnd - frameBegin) * ratio);
}

// A frame that may compile a pipeline gets this many times the policy's hang floor.
constexpr double kFirstFrameFloors = 10.0;

std::chrono::nanoseconds EditLoop::frameLimit() const {
  const double floor = session_.context().policy().hangSeconds;
  const double typical = median(std::vector<double>(frameSeconds_.begin(), frameSeconds_.end()));
  double limit = std::max(floor, 50.0 * typical);
  // A first frame may compile its pipeline (the driver's JIT, where the warm-up did not): ten floors.
  if (awaitingFirstFrame_ || frameSeconds_.empty()) limit = std::max(limit, kFirstFrameFloors * floor);
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(limit));
}

std::chrono::nanoseconds EditLoop::compilingFrameLimit() const {
  const double floor = session_.context().policy().hangSeconds;
  return std::max(frameLimit(), std::chrono::duration_cast<std::chrono::nanoseconds>(
                                    std::chrono::duration<double>(kFirstFrameFloors * floor)));
}

std::string EditLoop::hangMessage(double seconds) const {
  char s[32];
  std::snprintf(s, sizeof s, "%.1f", seconds);
  std::string files;
  if (const auto last = hot_->lastEvent())
    for (const auto& f : last->filesChanged) files += (files.empty() ? "" : ", ") + f;
  return std::string("a frame did not finish in ") + s + " s" +
         (files.empty() ? std::string() : " after the reload of " + files) +
         ": an endless loop the trial frame did not meet? The device cannot stop it: the workbench ends (the "
         "files on disk are as saved; fix them before the next start)";
}

std::vector<std::filesystem::path> EditLoop::revert(const std::vector<HotReload::InstalledPass>& installed) {
  auto unknown = hot_->revert(installed);
  if (comparison_) comparison_->reset();
  return unknown;
}

}  // namespace wb::live
