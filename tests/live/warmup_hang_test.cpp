// When a hot reload's warm-up frame counts as hung (live/jit_warmup.h): past its limit of wall time, unless
// the device runs on the CPU and its driver threads have not spent that limit in CPU time (a machine busy
// with other work starves the warm-up, which runs at a lowered priority); then up to 20 limits. And the
// per-thread CPU time that tells the two apart (common/thread_cpu.h).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "common/thread_cpu.h"
#include "live/jit_warmup.h"

namespace {

using wb::live::warmupFrameMayStillFinish;

TEST(WarmupHang, AFrameWithinItsLimitIsWaitedFor) {
  EXPECT_TRUE(warmupFrameMayStillFinish(2.9, 0.0, 3.0, false));
  EXPECT_TRUE(warmupFrameMayStillFinish(2.9, 50.0, 3.0, true));
}

TEST(WarmupHang, OnAGpuTheWallClockAloneDecides) {
  EXPECT_FALSE(warmupFrameMayStillFinish(3.0, 0.0, 3.0, false));
  EXPECT_FALSE(warmupFrameMayStillFinish(100.0, 0.0, 3.0, false));
}

TEST(WarmupHang, OnTheCpuAStarvedFrameIsWaitedForAndASpinningOneIsNot) {
  // Starved: past its wall limit with less than the limit of CPU spent.
  EXPECT_TRUE(warmupFrameMayStillFinish(10.0, 0.5, 3.0, true));
  EXPECT_TRUE(warmupFrameMayStillFinish(59.0, 2.9, 3.0, true));
  // Spinning (an endless loop spends CPU at the wall clock's pace, or faster on several threads).
  EXPECT_FALSE(warmupFrameMayStillFinish(3.0, 3.0, 3.0, true));
  EXPECT_FALSE(warmupFrameMayStillFinish(3.1, 6.0, 3.0, true));
  // Twenty limits end the wait all the same.
  EXPECT_FALSE(warmupFrameMayStillFinish(60.0, 0.0, 3.0, true));
}

// A thread that spins accrues CPU time; one that waits does not; both are the threads started since.
TEST(ThreadCpu, ASpinningThreadSpendsCpuAndAWaitingOneDoesNot) {
  const auto before = wb::threadIds();
  ASSERT_FALSE(before.empty()) << "/proc/self/task is not readable";
  std::atomic<bool> stop{false};
  std::mutex m;
  std::condition_variable cv;
  std::thread spinning([&] {
    volatile double x = 1.0;
    while (!stop.load(std::memory_order_relaxed)) x = x * 1.0000001 + 1e-9;
  });
  std::thread waiting([&] {
    std::unique_lock lock(m);
    cv.wait(lock, [&] { return stop.load(); });
  });
  const auto started = wb::threadsStartedSince(before, wb::threadIds());
  ASSERT_EQ(started.size(), 2u);
  const auto atStart = wb::threadCpuSeconds(started);
  ASSERT_EQ(atStart.size(), 2u);
  // Until the two threads have spent 0.3 s of CPU between them (a cap for a busy machine, not a timing).
  double spent = 0;
  for (auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
       spent < 0.3 && std::chrono::steady_clock::now() < deadline;)
    spent = wb::cpuSecondsBetween(atStart, wb::threadCpuSeconds(started));
  const auto now = wb::threadCpuSeconds(started);
  {
    std::lock_guard lock(m);
    stop = true;
  }
  cv.notify_all();
  spinning.join();
  waiting.join();
  EXPECT_GE(spent, 0.3);
  // Which of the two is which: the waiting one spent (nearly) nothing, the spinning one the rest.
  double least = 1e30, most = 0;
  for (const auto& [id, s] : now) {
    const double d = s - atStart.at(id);
    least = std::min(least, d);
    most = std::max(most, d);
  }
  EXPECT_LT(least, 0.05);
  EXPECT_GE(most, 0.25);
  // Ended threads are left out.
  EXPECT_TRUE(wb::threadCpuSeconds(started).empty());
}

}  // namespace
