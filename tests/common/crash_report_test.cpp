// tests/crash_report.cpp, linked into every test executable: a test process that dies of a signal names the
// signal and prints its thread's call stack, with this executable's own function names.
#include <gtest/gtest.h>

#include <csignal>

// External linkage: the dynamic symbol table (-rdynamic) names it in the printed call stack. It raises the
// signal rather than calling abort(), whose call the compiler moves out to a local ".cold" part.
__attribute__((noinline)) void wbCrashReportAbortsHere() {
  std::raise(SIGABRT);
  asm volatile("" ::: "memory");  // keeps this frame: no tail call to raise()
}

namespace {

TEST(CrashReport, AnAbortPrintsTheSignalAndTheCallStack) {
  EXPECT_DEATH(wbCrashReportAbortsHere(),
               "fatal signal 6 \\(ABRT\\) in thread [0-9]+.*call stack:(.|\n)*wbCrashReportAbortsHere");
}

}  // namespace
