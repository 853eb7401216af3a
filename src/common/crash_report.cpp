#include "common/crash_report.h"

#include <execinfo.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <csignal>
#include <cstring>

namespace wb {
namespace {

const char* gProgram = "";

// Only async-signal-safe calls below: write(2), backtrace_symbols_fd(3), and backtrace(3) after its first
// call (installCrashReport makes it).
void say(const char* text) {
  if (::write(STDERR_FILENO, text, std::strlen(text)) < 0) return;
}

// The decimal digits of v, without printf (not async-signal-safe).
void sayNumber(long v) {
  char digits[24];
  int i = sizeof digits;
  digits[--i] = '\0';
  do {
    digits[--i] = char('0' + v % 10);
    v /= 10;
  } while (v > 0 && i > 0);
  say(digits + i);
}

void onFatalSignal(int sig) {
  const long tid = ::syscall(SYS_gettid);
  say("\n*** ");
  say(gProgram);
  say(": fatal signal ");
  sayNumber(sig);
  say(" (");
  const char* name = sigabbrev_np(sig);
  say(name ? name : "?");
  say(") in thread ");
  sayNumber(tid);
  say(tid == ::getpid() ? " (the main thread)" : "");
  say("; its call stack:\n");
  void* frames[96];
  const int n = ::backtrace(frames, 96);
  ::backtrace_symbols_fd(frames, n, STDERR_FILENO);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void installCrashReport(const char* program) {
  gProgram = program;
  void* warm[1];
  ::backtrace(warm, 1);  // loads the unwinder now: its first call allocates, which a handler must not
  struct sigaction sa {};
  sa.sa_handler = onFatalSignal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGABRT, &sa, nullptr);
#if !defined(__SANITIZE_ADDRESS__)
  ::sigaction(SIGSEGV, &sa, nullptr);
  ::sigaction(SIGBUS, &sa, nullptr);
  ::sigaction(SIGFPE, &sa, nullptr);
  ::sigaction(SIGILL, &sa, nullptr);
#endif
}

}  // namespace wb
