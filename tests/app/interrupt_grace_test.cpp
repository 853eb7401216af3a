// InterruptRequest: a command that cannot stop after SIGINT/SIGTERM (blocked on a device that never finishes
// a frame) is ended at the end of its grace with the signal's status; one that stops in time ends as it
// wants.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "app/progress.h"

namespace {

// Runs `body` in a child process; returns its wait status, or -1 when it did not end within `capSeconds` (it
// is killed then).
template <class Body>
int inChild(Body body, double capSeconds) {
  const pid_t pid = fork();
  if (pid == 0) {
    body();
    _exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(capSeconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

}  // namespace

TEST(InterruptGrace, ACommandBlockedAfterTheSignalIsEndedWithTheSignalsStatus) {
  const int status = inChild(
      [] {
        wb::app::InterruptRequest interrupt(0.5);
        raise(SIGTERM);
        for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));  // never looks at the request
      },
      120);
  ASSERT_NE(status, -1) << "the process did not end after SIGTERM";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
}

TEST(InterruptGrace, ACommandThatStopsInTimeEndsAsItWants) {
  const int status = inChild(
      [] {
        {
          wb::app::InterruptRequest interrupt(30.0);
          raise(SIGINT);
          while (!interrupt.requested()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        _exit(7);
      },
      120);
  ASSERT_NE(status, -1);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 7);
}

TEST(InterruptGrace, TheGraceCoversThreeOfTheLongestUnitsOfWork) {
  const int status = inChild(
      [] {
        wb::app::InterruptRequest interrupt(0.1);
        interrupt.noteWorkSeconds(2.0);  // a sample of 2 s is in progress: 6 s of grace
        raise(SIGINT);
        std::this_thread::sleep_for(std::chrono::seconds(1));  // the sample finishes and is written
        _exit(9);
      },
      120);
  ASSERT_NE(status, -1);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 9) << "ended before the work in progress could finish";
}
