// What a rebuild costs the frames drawn meanwhile, against the frames before the edit (watch log keys and the
// window's reload history): synthetic frame times with known answers.
#include <gtest/gtest.h>

#include "live/reload_frames.h"

using namespace wb::live;
using Clock = ReloadFrameTimeline::Clock;
using std::chrono::milliseconds;

namespace {

// Frames back to back from t, each lasting ms[i]; returns the end of the last.
Clock::time_point addFrames(ReloadFrameTimeline& t, Clock::time_point at, std::initializer_list<int> ms) {
  for (int m : ms) {
    t.add(at, at + milliseconds(m));
    at += milliseconds(m);
  }
  return at;
}

}  // namespace

TEST(ReloadFrames, SplitsFramesAtTheEditAndTakesTheLastAsTheFirstNewOne) {
  ReloadFrameTimeline t;
  auto at = Clock::time_point{} + milliseconds(1000);
  // 25 frames before the edit: the median looks at the last 20 (10 ms each; the five oldest were 50 ms).
  at = addFrames(t, at, {50, 50, 50, 50, 50});
  for (int i = 0; i < 20; ++i) at = addFrames(t, at, {i == 17 ? 14 : 10});
  const auto edit = at + milliseconds(2);
  // During the rebuild: 12 and 16 ms frames (the first straddles the edit: it ended after it), then the first
  // frame with the new pipeline, 40 ms.
  at = addFrames(t, at, {12, 16, 12, 40});
  const auto s = t.stats(edit, true);
  EXPECT_DOUBLE_EQ(s.medianBefore, 10.0);
  EXPECT_DOUBLE_EQ(s.maxDuringRebuild, 16.0);
  EXPECT_DOUBLE_EQ(s.firstNewFrame, 40.0);
  EXPECT_EQ(s.framesDuringRebuild, 3);
  // Control span: as long as edit -> last frame end (78 ms) before the edit: holds the 14 ms frame (it ended
  // 2 + 2 * 10 ms before the edit) but none of the 50 ms ones.
  EXPECT_DOUBLE_EQ(s.maxBeforeSameSpan, 14.0);

  // Nothing rebuilt (a failed build): no first new frame; every frame after the edit counts as during.
  const auto f = t.stats(edit, false);
  EXPECT_DOUBLE_EQ(f.firstNewFrame, -1.0);
  EXPECT_DOUBLE_EQ(f.maxDuringRebuild, 40.0);
  EXPECT_EQ(f.framesDuringRebuild, 4);
}

TEST(ReloadFrames, KeepsTenSecondsOfFrames) {
  ReloadFrameTimeline t;
  const auto begin = Clock::time_point{} + milliseconds(1000);
  auto at =
      addFrames(t, begin, {900});  // more than ten seconds older than the last frame once the rest is in
  for (int i = 0; i < 110; ++i) at = addFrames(t, at, {100});
  // An edit before every frame kept: all of them count as during the rebuild; the 900 ms one is gone.
  EXPECT_DOUBLE_EQ(t.stats(begin, false).maxDuringRebuild, 100.0);
  ReloadFrameTimeline empty;
  EXPECT_DOUBLE_EQ(empty.stats(at, true).firstNewFrame, -1.0);
}

// No frame before the edit (an edit during the very first frame): the median before is "none" (-1), not 0.
TEST(ReloadFrames, NoSuchFrameIsMinusOneNotZero) {
  ReloadFrameTimeline t;
  const auto edit = Clock::time_point{} + milliseconds(1000);
  addFrames(t, edit + milliseconds(5), {30});
  const auto s = t.stats(edit, true);
  EXPECT_DOUBLE_EQ(s.medianBefore, -1.0);
  EXPECT_DOUBLE_EQ(s.maxBeforeSameSpan, -1.0);
  EXPECT_DOUBLE_EQ(s.maxDuringRebuild, -1.0);
  EXPECT_DOUBLE_EQ(s.firstNewFrame, 30.0);
}
