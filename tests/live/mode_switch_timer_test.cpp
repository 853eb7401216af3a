// ModeSwitchTimer on made-up times: what the window's stats report for a mode switch.
#include <gtest/gtest.h>

#include "live/mode_switch_timer.h"

namespace {

using wb::live::ModeSwitchTimer;
using Clock = ModeSwitchTimer::Clock;

Clock::time_point at(double ms) {
  return Clock::time_point(
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(ms)));
}

TEST(ModeSwitchTimer, TimesFromTheRequestToTheNewModesSecondFrame) {
  ModeSwitchTimer t;
  t.frame(at(0), at(50));  // no switch: nothing timed
  EXPECT_TRUE(t.records().empty());
  // A converging loop presented at 1000 ms and traced without presenting until the request at 1900 ms.
  t.requested("hybrid", at(1900));
  t.frame(at(1000), at(1960));  // the interval the request fell into: only its last 60 ms are the switch's
  t.frame(at(1960), at(2010));
  t.tookEffect(at(2010));
  t.frame(at(2010), at(2310));  // the new mode's first frame
  t.frame(at(2310), at(2400));  // and second: the last one timed
  t.frame(at(2400), at(3400));
  ASSERT_EQ(t.records().size(), 1u);
  const auto& r = t.records()[0];
  EXPECT_EQ(r.to, "hybrid");
  EXPECT_TRUE(r.done);
  EXPECT_NEAR(r.prepareMs, 110.0, 1e-6);
  EXPECT_NEAR(r.longestFrameMs, 300.0, 1e-6);
  EXPECT_NEAR(r.totalMs, 500.0, 1e-6);
  EXPECT_EQ(r.frames, 4u);
  EXPECT_FALSE(t.timing());
}

TEST(ModeSwitchTimer, ASwitchBackBeforeTheModeIsReadyStaysNotDone) {
  ModeSwitchTimer t;
  t.requested("reflections", at(0));
  EXPECT_TRUE(t.timing());
  ASSERT_EQ(t.records().size(), 1u);
  EXPECT_EQ(t.records()[0].to, "reflections");
  t.frame(at(0), at(40));
  t.cancelled();
  t.frame(at(40), at(5000));
  EXPECT_FALSE(t.timing());
  ASSERT_EQ(t.records().size(), 1u);
  EXPECT_FALSE(t.records()[0].done);
  EXPECT_NEAR(t.records()[0].longestFrameMs, 40.0, 1e-6);
  t.tookEffect(at(6000));  // a later effect without a request times nothing
  EXPECT_FALSE(t.records()[0].done);
}

}  // namespace
