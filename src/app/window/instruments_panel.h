// The panel's instruments (live::Instruments): GPU time per pass (a table and a graph of recent frames), the
// cost views' numbers (or why there is no cost data; their colour bar is over the image, heat_legend.h), the
// asserts toggle with its first failures and their marks on the image, and the inspected sample's wbPrint
// records.
#pragma once
#include "app/window/rect.h"
#include "live/live_session.h"

namespace wb::app {

// Stats: each pass's GPU milliseconds in the last frame (`displayMs`: the window's display pass; the
// denoiser's at its last run while denoising) and the graph of the frames' GPU time.
void drawPassTimes(const live::LiveSession& session, double displayMs);
// Inspect, under the debug view: the cost and inefficiency views' scale and statistics.
void drawCostSummary(const live::LiveSession& session);
// Inspect: the asserts variant's toggle and its failures.
void drawAssertsSection(live::LiveSession& session);
// Inspect, under the path inspector: the shown sample's prints in the order it made them.
void drawPrintsSection(const live::LiveSession& session);
// Over the image: the pixels whose asserts failed.
void drawAssertMarks(const live::LiveSession& session, const Rect& image);

}  // namespace wb::app
