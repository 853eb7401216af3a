// What a live session shows of the A/B comparison after each edit (live/ab_comparison.h): whether edits are
// compared, the last comparison's verdicts and images per compared pipeline (tonemapped, and the difference
// in false colour with its scale), the budget it ran with (live/ab_budget.h), what Revert would reinstall,
// the user's Revert/Accept (applied by the session at a frame boundary), and whether its panel is open.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "live/ab_budget.h"
#include "live/ab_comparison.h"
#include "live/hot_reload.h"

namespace wb::live {

struct ABState {
  enum class Show { Old, New, Split, Difference };

  // One compared pipeline: its verdicts and its images.
  struct View {
    ReloadAB result;
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> oldRgba, newRgba,
        diffRgba;          // tonemapped (display sRGB) and the false-colour difference
    double diffScale = 0;  // radiance at the top of the false-colour scale
  };

  // Whether edits are compared: on until the user says otherwise (the budget follows the machine instead of
  // the comparison switching itself off).
  bool enabled = true;

  std::vector<ReloadAB> results;                    // the last comparison, the active renderer's first
  std::vector<View> views;                          // the same, with their images
  std::vector<HotReload::InstalledPass> installed;  // what Revert reinstalls
  ABPlan plan;                                      // the budget it ran with
  double abMs = -1, editMs = -1;  // the last comparison's cost and its edit's time (edit to first frame)
  std::string note;               // what Revert/Accept did, or why the comparison failed
  bool decided = false;           // Revert or Accept was pressed for the last comparison
  bool revertRequested = false, acceptRequested = false;

  // The panel: open when a comparison arrives; closed by its close button, and after Revert or Accept unless
  // pinned.
  bool open = false;
  bool pinned = false;

  Show show = Show::Split;

  // Takes a comparison's outcomes (the active renderer's first), the programs it compared, the plan it ran
  // with and its cost against the edit's time; opens the panel.
  void set(const std::vector<ABOutcome>& outcomes, const std::vector<HotReload::InstalledPass>& programs,
           const ABPlan& plan, double ms, double editToFirstFrameMs);
  // Revert or Accept was applied: the panel closes unless pinned.
  void decide(const std::string& what);
  // The compared pipeline of the mode `mode` ("pathtrace", "hybrid", "reflections") to show, or nullptr when
  // the last edit rebuilt none of its pipelines.
  const View* viewFor(const std::string& mode) const;
};

}  // namespace wb::live
