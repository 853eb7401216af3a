#include "app/progress.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>

namespace wb::app {
namespace {

constexpr double kTerminalPeriod = 0.25;  // seconds between rewrites of the terminal line
constexpr double kLogPeriod = 5.0;        // seconds between plain lines

std::atomic<int> gSignal{0};

void onSignal(int sig) {
  gSignal = sig;
}

std::string duration(double s) {
  char b[32];
  if (s < 60) {
    std::snprintf(b, sizeof b, "%.1f s", s);
  } else if (s < 3600) {
    std::snprintf(b, sizeof b, "%d min %02d s", int(s) / 60, int(s) % 60);
  } else {
    std::snprintf(b, sizeof b, "%d h %02d min", int(s) / 3600, (int(s) / 60) % 60);
  }
  return b;
}

}  // namespace

ProgressLine::ProgressLine(std::string what, std::string unit, uint64_t total)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      terminal_(::isatty(STDERR_FILENO) == 1) {}

void ProgressLine::update(uint64_t done, double seconds) {
  const bool first = !printed_;
  const double period = terminal_ ? kTerminalPeriod : kLogPeriod;
  if (!first && seconds - lastPrint_ < period && done < total_) return;
  if (!terminal_ && done >= total_ && !first) return;  // the command's own last line says it is done
  lastPrint_ = seconds;
  printed_ = true;
  const double eta = done > 0 ? seconds / double(done) * double(total_ - std::min(done, total_)) : 0.0;
  std::fprintf(stderr, "%s%s: %llu/%llu %s  %s elapsed  ETA %s%s", terminal_ ? "\r" : "", what_.c_str(),
               static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_), unit_.c_str(),
               duration(seconds).c_str(), duration(eta).c_str(), terminal_ ? "   " : "\n");
  std::fflush(stderr);
}

void ProgressLine::finish() {
  if (terminal_ && printed_) std::fputc('\n', stderr);
  printed_ = false;
}

InterruptRequest::InterruptRequest() {
  gSignal = 0;
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // a second Ctrl-C ends the process
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

InterruptRequest::~InterruptRequest() {
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
}

bool InterruptRequest::requested() const {
  return gSignal != 0;
}

int InterruptRequest::signal() const {
  return gSignal;
}

}  // namespace wb::app
