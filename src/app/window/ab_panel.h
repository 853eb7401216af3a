// The window's A/B panel: after each edit, the image and speed verdicts of old against new for the mode in
// use (the session's comparison, live/ab_state.h), a flip / split / difference view of the two images (the
// difference in false colour with its scale), the budget the comparison ran with, and Revert (reinstall the
// old pipeline) / Accept, which the session applies. A normal ImGui window: moved, collapsed and closed by
// the user, closed after Revert or Accept unless pinned.
#pragma once
#include <string>

#include "live/ab_state.h"

namespace wb::app {

// The A/B panel while it is open, first placed over the bottom-right corner of the view that ends at
// (viewRight, viewBottom). `mode`: the mode in use ("pathtrace", ...), whose comparison it shows.
void drawABPanel(live::ABState& v, const std::string& mode, float viewRight, float viewBottom);

}  // namespace wb::app
