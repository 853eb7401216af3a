#include "live/reload_frames.h"

#include <algorithm>
#include <vector>

#include "common/statistics.h"

namespace wb::live {
namespace {

double ms(ReloadFrameTimeline::Clock::time_point a, ReloadFrameTimeline::Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

void ReloadFrameTimeline::add(Clock::time_point begin, Clock::time_point end) {
  frames_.push_back({begin, end});
  while (frames_.size() > 2 && ms(frames_.front().end, frames_.back().end) > 10000.0) frames_.pop_front();
}

ReloadFrameStats ReloadFrameTimeline::stats(Clock::time_point editSeen, bool lastIsFirstNew) const {
  ReloadFrameStats s;
  if (frames_.empty()) return s;
  std::vector<double> before;
  // The control span: as long as from the edit to the last frame, right before the edit.
  const double span = ms(editSeen, frames_.back().end);
  for (size_t i = 0; i < frames_.size(); ++i) {
    const auto& f = frames_[i];
    const double length = ms(f.begin, f.end);
    if (f.end <= editSeen) {
      before.push_back(length);
      if (ms(f.end, editSeen) <= span) s.maxBeforeSameSpan = std::max(s.maxBeforeSameSpan, length);
    } else if (lastIsFirstNew && i + 1 == frames_.size()) {
      s.firstNewFrame = length;  // includes any compile the driver left for the first dispatch
    } else {
      s.maxDuringRebuild = std::max(s.maxDuringRebuild, length);
      ++s.framesDuringRebuild;
    }
  }
  if (before.size() > 20) before.erase(before.begin(), before.end() - 20);
  if (!before.empty()) s.medianBefore = median(before);
  return s;
}

}  // namespace wb::live
