#include "live/ab_state.h"

#include <cmath>

#include "eval/metrics.h"

namespace wb::live {

void ABState::set(const std::vector<ABOutcome>& outcomes,
                  const std::vector<HotReload::InstalledPass>& programs, const ABPlan& p, double ms,
                  double editToFirstFrameMs) {
  results.clear();
  views.clear();
  for (const auto& o : outcomes) {
    results.push_back(o.result);
    View v;
    v.result = o.result;
    v.width = o.oldImage.width;
    v.height = o.oldImage.height;
    v.oldRgba = eval::tonemapToSrgb8(o.oldImage);
    v.newRgba = eval::tonemapToSrgb8(o.newImage);
    // Full scale at the largest difference, so that a change on a few pixels stays visible (a NaN/Inf
    // difference: the 99th percentile instead).
    const double largest = o.result.image.maxAbsDiff;
    v.diffRgba =
        eval::errorHeatmap(o.oldImage, o.newImage, std::isfinite(largest) ? largest : 0.0, &v.diffScale);
    views.push_back(std::move(v));
  }
  installed = programs;
  plan = p;
  abMs = ms;
  editMs = editToFirstFrameMs;
  decided = false;
  note.clear();
  open = true;
}

void ABState::decide(const std::string& what) {
  note = what;
  decided = true;
  if (!pinned) open = false;
}

const ABState::View* ABState::viewFor(const std::string& mode) const {
  for (const auto& v : views)
    if (v.result.mode == mode) return &v;
  return nullptr;
}

}  // namespace wb::live
