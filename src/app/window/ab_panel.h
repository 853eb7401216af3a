// The window's A/B panel: after each edit, the image and speed verdicts of old against new (the A/B
// comparison, render/ab_comparison.h), a flip / split / difference view of the two images (the difference in
// false colour with its scale), and Revert (reinstall the old pipeline) / Accept. The frame loop runs the
// comparison and applies the buttons; this only holds what is shown and what was asked.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "live/ab_comparison.h"
#include "live/hot_reload.h"

namespace wb::app {

struct ABView {
  enum class Show { Old, New, Split, Difference };

  // Whether edits are compared: on by default; switched off after a comparison that cost more than
  // kMaxCostRatio of the edit time, unless the user chose with the toggle.
  bool enabled = true;
  bool userChose = false;
  static constexpr double kMaxCostRatio = 0.2;

  std::vector<live::ReloadAB> results;                    // the last comparison, the active renderer's first
  std::vector<live::HotReload::InstalledPass> installed;  // what Revert reinstalls
  double abMs = -1, editMs = -1;  // the last comparison's cost and its edit's time (edit to first frame)
  std::string note;               // why the comparison was switched off, or what Revert/Accept did
  bool decided = false;           // Revert or Accept was pressed for the last comparison
  bool revertRequested = false, acceptRequested = false;

  Show show = Show::Split;
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> oldRgba, newRgba,
      diffRgba;          // tonemapped (display sRGB) and the false-colour difference
  double diffScale = 0;  // radiance at the top of the false-colour scale

  // Takes a comparison's outcomes (shown: the first), the programs it compared and its cost against the
  // edit's time; switches the comparison off when it costs too much (see `enabled`).
  void set(const std::vector<live::ABOutcome>& outcomes,
           const std::vector<live::HotReload::InstalledPass>& programs, double ms, double editToFirstFrameMs);
};

// The A/B panel (an ImGui window over the image's bottom-right corner), when there is a comparison or the
// toggle to show.
void drawABPanel(ABView& v, float viewRight, float viewBottom);

}  // namespace wb::app
