// The window's A/B comparison after each edit (ab_panel.h): run after the new image's first frame, shown in
// the A/B panel, with Revert and Accept.
#include <cstdio>

#include "app/window/workbench_window.h"

namespace wb::app {

void WorkbenchWindow::showCompletedReloads() {
  for (auto& c : loop_->takeCompleted()) {
    if (!c.abError.empty()) {
      ab_.note = "A/B failed: " + c.abError;
      continue;
    }
    if (c.ab.empty()) continue;
    ab_.set(c.ab, c.installed, c.event.abMs, c.event.editToFirstFrameMs);
  }
  loop_->setAB(ab_.enabled);
}

void WorkbenchWindow::applyABDecision() {
  if (ab_.revertRequested && !ab_.decided && !ab_.installed.empty()) {
    loop_->revert(ab_.installed);
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
