#include "live/ab_state.h"

#include <cmath>
#include <cstdio>

#include "eval/metrics.h"

namespace wb::live {

void ABState::set(const std::vector<ABOutcome>& outcomes,
                  const std::vector<HotReload::InstalledPass>& programs, double ms,
                  double editToFirstFrameMs) {
  results.clear();
  for (const auto& o : outcomes) results.push_back(o.result);
  installed = programs;
  abMs = ms;
  editMs = editToFirstFrameMs;
  decided = false;
  note.clear();
  width = height = 0;
  oldRgba.clear();
  newRgba.clear();
  diffRgba.clear();
  if (!outcomes.empty()) {
    const auto& o = outcomes.front();
    width = o.oldImage.width;
    height = o.oldImage.height;
    oldRgba = eval::tonemapToSrgb8(o.oldImage);
    newRgba = eval::tonemapToSrgb8(o.newImage);
    // Full scale at the largest difference, so that a change on a few pixels stays visible (a NaN/Inf
    // difference: the 99th percentile instead).
    const double largest = results.front().image.maxAbsDiff;
    diffRgba = eval::errorHeatmap(o.oldImage, o.newImage, std::isfinite(largest) ? largest : 0.0, &diffScale);
  }
  if (!userChose && editMs > 0 && abMs > kMaxCostRatio * editMs) {
    enabled = false;
    char buf[160];
    std::snprintf(buf, sizeof buf, "off: the comparison took %.0f ms, over %.0f%% of the edit's %.0f ms",
                  abMs, kMaxCostRatio * 100.0, editMs);
    note = buf;
  }
}

}  // namespace wb::live
