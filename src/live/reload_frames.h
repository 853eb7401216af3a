// Frame times around a hot reload: what a rebuild costs the frames the render loop draws meanwhile, against
// the frames before the edit. Kept by HotReload for `watch` and the window alike.
#pragma once
#include <chrono>
#include <deque>

namespace wb::live {

// Frame times in ms; -1 where there was no such frame (the logs write null there, not a time of 0).
struct ReloadFrameStats {
  double medianBefore = -1;       // median of the (up to 20) frames that ended before the edit was seen
  double maxDuringRebuild = -1;   // slowest frame that ended after the edit, the first new frame excluded
  double maxBeforeSameSpan = -1;  // slowest frame of as long a span just before the edit: the noise floor
  double firstNewFrame = -1;      // the first frame with the new pipelines (none, e.g., after a failed build)
  int framesDuringRebuild = 0;    // frames that ended after the edit, the first new frame excluded
};

class ReloadFrameTimeline {
 public:
  using Clock = std::chrono::steady_clock;
  // A finished frame; keeps ten seconds of them (a rebuild on a fast GPU spans thousands of short frames).
  void add(Clock::time_point begin, Clock::time_point end);
  // For an edit seen at editSeen; with lastIsFirstNew the last frame added is the first with the new
  // pipelines.
  ReloadFrameStats stats(Clock::time_point editSeen, bool lastIsFirstNew) const;

 private:
  struct Frame {
    Clock::time_point begin, end;
  };
  std::deque<Frame> frames_;
};

}  // namespace wb::live
