#include "app/progress.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>

namespace wb::app {
namespace {

constexpr double kTerminalPeriod = 0.25;  // seconds between rewrites of the terminal line
constexpr double kLogPeriod = 5.0;        // seconds between plain lines

std::atomic<int> gSignal{0};
int gWakeFd = -1;  // the grace thread's pipe (write end)

void onSignal(int sig) {
  gSignal = sig;
  if (gWakeFd >= 0) {
    const char c = 's';
    [[maybe_unused]] auto n = ::write(gWakeFd, &c, 1);  // async-signal-safe
  }
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

ProgressLine::ProgressLine(std::string what)
    : what_(std::move(what)),
      terminal_(::isatty(STDERR_FILENO) == 1),
      phaseStart_(Clock::now()),
      lastUpdate_(phaseStart_) {}

void ProgressLine::update(const std::string& label, double fraction, const std::string& detail, bool force) {
  const auto now = Clock::now();
  // A phase begins where the previous one's work ended: at its last update, or at finish() (the first phase:
  // when this object was made).
  const bool newPhase = !started_ || label != label_;
  if (started_ && newPhase) phaseStart_ = lastUpdate_;
  started_ = true;
  label_ = label;
  lastUpdate_ = now;
  const double period = terminal_ ? kTerminalPeriod : kLogPeriod;
  if (!newPhase && !force && std::chrono::duration<double>(now - lastPrint_).count() < period) return;
  lastPrint_ = now;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(now - phaseStart_).count();
  const std::string eta = fraction <= 0.0   ? "?"
                          : fraction >= 1.0 ? "0 s"
                                            : duration(elapsed / fraction * (1.0 - fraction));
  constexpr int kWidth = 24;
  const int filled = int(fraction * kWidth + 0.5);
  std::fprintf(stderr, "%s%s: %s%s[%s%s] %3d%% %s  %s elapsed  ETA %s%s", terminal_ ? "\r" : "",
               what_.c_str(), label.c_str(), label.empty() ? "" : " ",
               std::string(size_t(filled), '#').c_str(), std::string(size_t(kWidth - filled), '.').c_str(),
               int(fraction * 100.0), detail.c_str(), duration(elapsed).c_str(), eta.c_str(),
               terminal_ ? "\033[K" : "\n");
  std::fflush(stderr);
  shown_ = terminal_;
}

void ProgressLine::finish() {
  if (shown_) std::fputc('\n', stderr);
  shown_ = false;
  started_ = false;
  phaseStart_ = lastUpdate_ = Clock::now();
}

void ProgressLine::note(const std::string& line) {
  std::fprintf(stderr, "%s%s\n", shown_ ? "\r\033[K" : "", line.c_str());
  std::fflush(stderr);
  shown_ = false;
}

StepProgress::StepProgress(std::string what, int totalSteps) : line_(std::move(what)), total_(totalSteps) {
  ticker_ = std::thread([this] {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, std::chrono::duration<double>(kTerminalPeriod));
      if (!stop_ && done_ >= 0) show(false);
    }
  });
}

StepProgress::~StepProgress() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  ticker_.join();
  line_.finish();
}

void StepProgress::step(const std::string& name) {
  std::lock_guard lock(mutex_);
  ++done_;
  name_ = name;
  show(true);
}

void StepProgress::note(const std::string& line) {
  std::lock_guard lock(mutex_);
  line_.note(line);
}

void StepProgress::show(bool force) {
  const double fraction = total_ > 0 ? double(std::min(done_, total_)) / double(total_) : 0.0;
  line_.update(
      "", fraction,
      "step " + std::to_string(std::min(done_ + 1, total_)) + "/" + std::to_string(total_) + ": " + name_,
      force);
}

InterruptRequest::InterruptRequest(double graceSeconds) {
  gSignal = 0;
  int fds[2];
  if (::pipe(fds) == 0) {
    wakeRead_ = fds[0];
    gWakeFd = wakeWrite_ = fds[1];
    // After a signal the command has `graceSeconds` to stop and write what it has; a command blocked where
    // it cannot look (a device that never finishes a frame) is ended then, with the signal's exit status.
    grace_ = std::thread([this, graceSeconds] {
      char c = 0;
      if (::read(wakeRead_, &c, 1) != 1 || c != 's') return;  // 'q': the request ended first
      const double grace = std::max(graceSeconds, 3.0 * workSeconds_.load());
      std::unique_lock lock(mutex_);
      if (done_.wait_for(lock, std::chrono::duration<double>(grace), [&] { return finished_; })) return;
      std::fprintf(stderr,
                   "workbench: still busy %.1f s after signal %d (the device does not finish its work): "
                   "ending now\n",
                   grace, gSignal.load());
      std::fflush(stdout);
      std::fflush(stderr);
      ::_exit(128 + gSignal);
    });
  }
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
  if (grace_.joinable()) {
    {
      std::lock_guard lock(mutex_);
      finished_ = true;
    }
    done_.notify_all();
    gWakeFd = -1;
    const char c = 'q';
    [[maybe_unused]] auto n = ::write(wakeWrite_, &c, 1);
    grace_.join();
  }
  if (wakeRead_ >= 0) ::close(wakeRead_);
  if (wakeWrite_ >= 0) ::close(wakeWrite_);
}

bool InterruptRequest::requested() const {
  return gSignal != 0;
}

int InterruptRequest::signal() const {
  return gSignal;
}

void InterruptRequest::noteWorkSeconds(double seconds) const {
  if (seconds > workSeconds_.load()) workSeconds_ = seconds;
}

}  // namespace wb::app
