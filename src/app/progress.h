// Progress of a long command on stderr, and Ctrl-C as a request to stop early. On a terminal one line is
// rewritten in place (a bar, what is done, elapsed time, ETA); otherwise a plain line is printed when a phase
// begins, every few seconds and when it ends, so logs stay short.
#pragma once
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace wb::app {

class ProgressLine {
 public:
  explicit ProgressLine(std::string what);  // the command's name ("render")
  // The current phase (`label`, "" for a command of one phase) is `fraction` done; `detail` says how far
  // ("12/256 spp"). A new label starts a new phase: the elapsed time and the ETA are the phase's. `force`
  // prints now (the end of a phase).
  void update(const std::string& label, double fraction, const std::string& detail, bool force = false);
  // Ends the terminal line (nothing when nothing is shown).
  void finish();
  // Prints a line of its own above the progress line.
  void note(const std::string& line);

 private:
  using Clock = std::chrono::steady_clock;
  std::string what_, label_;
  bool terminal_;
  bool shown_ = false;  // a terminal line is on screen
  bool started_ = false;
  Clock::time_point phaseStart_{}, lastUpdate_{}, lastPrint_{};
};

// A suite of steps of different lengths (the bench): each step is announced with its number, and a ticker
// keeps the line (elapsed time, ETA from the steps done so far) current while a step runs.
class StepProgress {
 public:
  StepProgress(std::string what, int totalSteps);
  ~StepProgress();
  StepProgress(const StepProgress&) = delete;
  StepProgress& operator=(const StepProgress&) = delete;
  // The previous step is done and `name` begins.
  void step(const std::string& name);
  void note(const std::string& line);

 private:
  void show(bool force);  // holds mutex_

  ProgressLine line_;
  int total_, done_ = -1;
  std::string name_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread ticker_;
};

// While alive, SIGINT and SIGTERM ask the command to stop (requested()); a second signal ends the process at
// once (the default action), and so does the end of `graceSeconds` after the first if the command is still
// running then (blocked on a device that never finishes its work): whatever the device is doing, a signal
// ends the process within a second or two, with the exit status 128 + the signal.
class InterruptRequest {
 public:
  explicit InterruptRequest(double graceSeconds = 2.0);
  ~InterruptRequest();
  InterruptRequest(const InterruptRequest&) = delete;
  InterruptRequest& operator=(const InterruptRequest&) = delete;
  bool requested() const;
  int signal() const;  // the signal received (0: none)
  // The command's longest unit of work so far (a sample, a frame): the grace after a signal is at least
  // three of them, so that the work in progress can finish and be written on a slow machine.
  void noteWorkSeconds(double seconds) const;

 private:
  mutable std::atomic<double> workSeconds_{0.0};
  int wakeRead_ = -1, wakeWrite_ = -1;
  std::thread grace_;
  std::mutex mutex_;
  std::condition_variable done_;
  bool finished_ = false;
};

}  // namespace wb::app
