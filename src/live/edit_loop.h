// The live-edit loop that a render loop drives, one object for `watch` and the window alike: hot reload of
// every pass of the session's renderers (and of passes the owner adds, such as the window's display), the
// frame times around each reload, the A/B comparison of old against new once the new image's first frame is
// drawn, and the rest a loop takes after a frame while a compile needs the cores of a CPU device.
//
// Per frame, on the render thread: beginFrame() installs what is ready; the owner records and submits its
// frame; frameFinished() once the frame's work is done; takeCompleted() hands over each reload that is over
// (a failure at once, an installed one after its first frame and comparison) to log or show.
#pragma once
#include <chrono>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "live/ab_budget.h"
#include "live/ab_comparison.h"
#include "live/hot_reload.h"
#include "render/render_session.h"

namespace wb::live {

struct EditLoopOptions {
  std::vector<std::filesystem::path> watchDirs;  // empty: shaders/
  bool ab = false;                               // compare old and new after each reload
  ABBudget budget;
  // The budget follows the machine (ab_budget.h): each comparison is cut to fit kMaxCostRatio of its edit's
  // time; false runs `budget` as given.
  bool adaptiveBudget = false;
};

// A reload that is over: its event (with the A/B results attached when a comparison ran), the comparison's
// images, and what Revert would reinstall.
struct CompletedReload {
  ReloadEvent event;
  std::vector<ABOutcome> ab;
  std::vector<HotReload::InstalledPass> installed;
  std::string abError;  // the comparison failed (a device error): why
  ABPlan abPlan;        // the budget the comparison ran with, and why
};

class EditLoop {
 public:
  using Clock = std::chrono::steady_clock;

  EditLoop(render::RenderSession& session, EditLoopOptions options);
  // Stops the hot reload and detaches from the session.
  ~EditLoop();
  EditLoop(const EditLoop&) = delete;
  EditLoop& operator=(const EditLoop&) = delete;

  HotReload& hot() { return *hot_; }
  const HotReload& hot() const { return *hot_; }
  // A pass of no renderer (the window's display) to reload too; it must outlive this object.
  void addPass(render::ReloadTarget& pass) { hot_->addPass(pass); }
  // Starts watching. `onReady` (optional) is called on the worker when something waits for beginFrame() (a
  // loop that sleeps between frames wakes up).
  void start(std::function<void()> onReady = {});

  // Render thread, at a frame boundary, before the frame is recorded: installs the pipelines that are ready.
  // Returns the event applied, if any (the UI shows it at once).
  std::optional<ReloadEvent> beginFrame();
  // Render thread, once the frame's work finished (frameBegin: when it began, after any rest). The first
  // frame after an install completes the reload: its frame times, then the A/B comparison when it is on.
  void frameFinished(Clock::time_point frameBegin);
  // The reloads that are over since the last call, oldest first.
  std::vector<CompletedReload> takeCompleted();

  // While a compile is in progress (HotReload::compiling): when a loop that drew a frame from frameBegin to
  // frameEnd should start its next one, resting `ratio` times as long as the frame took (the device
  // policy's watchRestRatio / windowRestRatio); frameEnd when nothing compiles or the ratio is 0.
  Clock::time_point restUntil(Clock::time_point frameBegin, Clock::time_point frameEnd, double ratio) const;
  bool compiling() const { return hot_->compiling(); }

  // The longest the next frame may take before it counts as hung: the device policy's floor or many times
  // the frames before it (not those that may have compiled a pipeline), and longer for the first frame with a
  // new pipeline (a driver that compiles at the first dispatch compiles it there when the warm-up could not).
  std::chrono::nanoseconds frameLimit() const;
  // The limit of a frame that may compile pipelines anywhere in it: frameLimit(), and at least its
  // first-frame allowance. The window's frames may run the display pass's, the denoiser's or a view's
  // pipelines for the first time (a CPU driver compiles them there), and its watchdog times a frame from its
  // submission.
  std::chrono::nanoseconds compilingFrameLimit() const;
  // What the user reads when a frame did not finish within frameLimit(): the last reload's files. A device
  // here cannot cancel the work, so the caller ends the process after saying it.
  std::string hangMessage(double seconds) const;

  // The A/B comparison: on or off (it runs with the budget given), and Revert of the last reload.
  bool abEnabled() const { return abOn_; }
  void setAB(bool on);
  // Makes the comparison's stand-in renderers now, so that the first comparison does not pay for them.
  void prepareAB();
  const ABBudget& abBudget() const { return budget_; }
  void setABBudget(const ABBudget& budget);
  // The live renderer's trace rate (pixel samples per ms): the adaptive budget's first guess of the machine.
  void setABRateHint(double pixelsPerMs) { planner_.setRateHint(pixelsPerMs); }
  const ABBudgetPlanner& abPlanner() const { return planner_; }
  // Reinstalls the pipelines the last reload replaced (`installed` from its CompletedReload).
  std::vector<std::filesystem::path> revert(const std::vector<HotReload::InstalledPass>& installed);

 private:
  render::RenderSession& session_;
  std::unique_ptr<HotReload> hot_;
  bool abOn_ = false;
  ABBudget budget_;
  bool adaptiveBudget_ = false;
  ABBudgetPlanner planner_;
  std::unique_ptr<ABComparison> comparison_;  // made on the first comparison
  bool awaitingFirstFrame_ = false;
  bool firstFrameDone_ = false;
  std::deque<double> frameSeconds_;  // the last frames' durations, those that may have compiled left out
  std::deque<CompletedReload> completed_;
};

}  // namespace wb::live
