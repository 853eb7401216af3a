// Runs a shell command line for the tests that drive the real `workbench` binary: its exit status and what it
// printed (stdout, and stderr too unless the line redirects it itself).
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace wb::testing {

struct CommandResult {
  int code = -1;  // exit status, or 128 + signal
  std::string output;
};

// Prefix for a command line that starts a program in a session of its own, as a user's terminal would
// (`setsid --wait`: the exit status is the program's). The kernel's autogroup scheduling then shares the CPU
// between it and the tests ctest runs beside it, as between two terminals.
inline constexpr const char* kOwnSession = "setsid --wait ";

inline CommandResult runCommand(const std::string& line, bool captureStderr = true) {
  CommandResult r;
  const std::string cmd = captureStderr ? line + " 2>&1" : line;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

}  // namespace wb::testing
