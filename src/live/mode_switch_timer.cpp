#include "live/mode_switch_timer.h"

#include <algorithm>

namespace wb::live {
namespace {

double msBetween(ModeSwitchTimer::Clock::time_point a, ModeSwitchTimer::Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

void ModeSwitchTimer::requested(const std::string& to, Clock::time_point t) {
  records_.push_back({to});
  start_ = t;
  timing_ = true;
  framesLeft_ = -1;
}

void ModeSwitchTimer::cancelled() {
  if (framesLeft_ < 0) timing_ = false;
}

void ModeSwitchTimer::tookEffect(Clock::time_point t) {
  if (!timing_ || framesLeft_ >= 0) return;
  records_.back().prepareMs = msBetween(start_, t);
  records_.back().done = true;
  framesLeft_ = 2;
}

void ModeSwitchTimer::frame(Clock::time_point begin, Clock::time_point end) {
  if (!timing_) return;
  Record& r = records_.back();
  r.longestFrameMs = std::max(r.longestFrameMs, msBetween(std::max(begin, start_), end));
  r.totalMs = msBetween(start_, end);
  ++r.frames;
  if (framesLeft_ > 0 && --framesLeft_ == 0) timing_ = false;
}

}  // namespace wb::live
