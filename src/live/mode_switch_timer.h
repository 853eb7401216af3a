// Times the window's mode switches as the user sees them: from the request, through the frames drawn while
// the other mode is made off the loop, to the new mode's second frame.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace wb::live {

class ModeSwitchTimer {
 public:
  using Clock = std::chrono::steady_clock;
  struct Record {
    std::string to;
    double prepareMs = 0;       // from the request until the new mode took effect
    double longestFrameMs = 0;  // the longest frame interval since the request (the part of it after)
    double totalMs = 0;         // from the request to the last frame timed
    uint64_t frames = 0;
    bool done = false;  // the new mode took effect
  };

  // A switch to `to` was asked for at `t`.
  void requested(const std::string& to, Clock::time_point t);
  // Switched back before the other mode was ready: the record stays, not done, and timing stops.
  void cancelled();
  // The new mode took effect at `t`; its next two frames are still timed.
  void tookEffect(Clock::time_point t);
  // One frame interval of the loop. The part before the request is not the switch's: a converging loop
  // presents once a second, and the request may come at any point of that second.
  void frame(Clock::time_point begin, Clock::time_point end);

  bool timing() const { return timing_; }
  Clock::time_point requestTime() const { return start_; }
  const std::vector<Record>& records() const { return records_; }

 private:
  std::vector<Record> records_;
  Clock::time_point start_{};
  bool timing_ = false;
  int framesLeft_ = 0;  // frames still timed after the switch took effect (-1: not yet in effect)
};

}  // namespace wb::live
