// Progress of a long command on stderr, and Ctrl-C as a request to stop early. On a terminal one line is
// rewritten in place (samples done, elapsed, ETA); otherwise a plain line is printed after the first sample
// and then every few seconds, so logs stay short.
#pragma once
#include <chrono>
#include <cstdint>
#include <string>

namespace wb::app {

class ProgressLine {
 public:
  // `what`: the command's name ("render"); `unit`: what is counted ("spp").
  ProgressLine(std::string what, std::string unit, uint64_t total);
  // After each unit of work; prints when due.
  void update(uint64_t done, double seconds);
  // Ends the terminal line (nothing when nothing was printed).
  void finish();

 private:
  std::string what_, unit_;
  uint64_t total_;
  bool terminal_;
  bool printed_ = false;
  double lastPrint_ = -1e9;
};

// While alive, SIGINT and SIGTERM ask the command to stop (interruptRequested()); a second signal ends the
// process at once (the default action).
class InterruptRequest {
 public:
  InterruptRequest();
  ~InterruptRequest();
  InterruptRequest(const InterruptRequest&) = delete;
  InterruptRequest& operator=(const InterruptRequest&) = delete;
  bool requested() const;
  int signal() const;  // the signal received (0: none)
};

}  // namespace wb::app
