// The window's A/B comparison after each edit (ab_panel.h): run after the new image's first frame, shown in
// the A/B panel, with Revert and Accept.
#include <chrono>
#include <cstdio>

#include "app/window/workbench_window.h"

namespace wb::app {

void WorkbenchWindow::noteReload(const std::optional<render::ReloadEvent>& event) {
  if (!event || event->pipelinesRebuilt.empty()) return;
  if (ab_.enabled) {
    abPending_ = true;
  } else if (abCompare_) {
    abCompare_->reset();  // its stand-ins no longer match what is installed
  }
}

void WorkbenchWindow::runPendingAB() {
  if (!abPending_) return;
  const auto last = hot_->lastEvent();
  if (!last || last->editToFirstFrameMs < 0) return;  // the new image is not on screen yet
  abPending_ = false;
  if (!abCompare_) abCompare_ = std::make_unique<render::ABComparison>(*session_);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<render::ABOutcome> outcomes;
  try {
    outcomes = abCompare_->compare(hot_->lastInstalled());
  } catch (const std::exception& e) {
    abCompare_->reset();
    ab_.note = std::string("A/B failed: ") + e.what();
    return;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<render::ReloadAB> results;
  for (const auto& o : outcomes) results.push_back(o.result);
  hot_->attachAB(results, ms);
  ab_.set(outcomes, hot_->lastInstalled(), ms, last->editToFirstFrameMs);
}

void WorkbenchWindow::applyABDecision() {
  if (ab_.revertRequested && !ab_.decided && !ab_.installed.empty()) {
    hot_->revert(ab_.installed);
    if (abCompare_) abCompare_->reset();
    ab_.note = "reverted to the old pipeline (the file on disk is unchanged)";
    ab_.decided = true;
    std::printf("workbench: A/B revert: old pipeline reinstalled\n");
    std::fflush(stdout);
  }
  if (ab_.acceptRequested && !ab_.decided) {
    ab_.note = "accepted";
    ab_.decided = true;
  }
  ab_.revertRequested = ab_.acceptRequested = false;
}

}  // namespace wb::app
