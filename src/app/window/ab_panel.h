// The window's A/B panel: after each edit, the image and speed verdicts of old against new (the session's
// comparison, live/ab_state.h), a flip / split / difference view of the two images (the difference in false
// colour with its scale), and Revert (reinstall the old pipeline) / Accept, which the session applies.
#pragma once
#include "live/ab_state.h"

namespace wb::app {

// The A/B panel (an ImGui window over the image's bottom-right corner), when there is a comparison or the
// toggle to show.
void drawABPanel(live::ABState& v, float viewRight, float viewBottom);

}  // namespace wb::app
