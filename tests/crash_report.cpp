// Linked into every test executable: when a test process dies of a fatal signal (an abort inside a driver's
// shader compiler, a segmentation fault), the dying thread and its call stack go to stderr, so a failure seen
// once on a CI machine says where it happened. The signal's default action follows: the process still dies
// of it, as ctest expects.
#include <execinfo.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <csignal>
#include <cstring>

namespace {

// Only async-signal-safe calls: write(2), backtrace_symbols_fd(3) (backtrace(3) after its first call).
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
  say("\n*** fatal signal ");
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

struct InstallCrashReport {
  InstallCrashReport() {
    void* warm[1];
    ::backtrace(warm, 1);  // loads the unwinder now: its first call allocates, which a handler must not
    struct sigaction sa {};
    sa.sa_handler = onFatalSignal;
    sigemptyset(&sa.sa_mask);
    ::sigaction(SIGABRT, &sa, nullptr);
#if !defined(__SANITIZE_ADDRESS__)
    // Under AddressSanitizer its own handler reports these.
    ::sigaction(SIGSEGV, &sa, nullptr);
    ::sigaction(SIGBUS, &sa, nullptr);
    ::sigaction(SIGFPE, &sa, nullptr);
    ::sigaction(SIGILL, &sa, nullptr);
#endif
  }
} installCrashReport;

}  // namespace
