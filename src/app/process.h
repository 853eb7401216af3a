// Running the workbench binary itself as a child process (benchmarks measure cold starts and hot reload the
// way a user sees them).
#pragma once
#include <map>
#include <string>
#include <sys/types.h>
#include <vector>

namespace wb::app {

std::string selfExecutable();

struct ChildProcess {
  pid_t pid = -1;
  // Starts `exe args...` with extra environment variables; stdout and stderr go to `logFile`.
  static ChildProcess spawn(const std::string& exe, const std::vector<std::string>& args,
                            const std::map<std::string, std::string>& env, const std::string& logFile);
  int wait();        // exit status (128 + signal when killed)
  void terminate();  // SIGTERM, then wait
};

}  // namespace wb::app
