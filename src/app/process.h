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
  bool ownSession = false;
  int exitStatus = -1;  // once reaped: the exit status (128 + signal when killed)  // the leader of a session
                        // of its own (terminate() signals the whole group)
  // Starts `exe args...` (a name without '/' is looked up in PATH) with extra environment variables; stdout
  // and stderr go to `logFile`. With `newSession` the child leads a new session and process group: what it
  // starts is scheduled apart from this process (the kernel's autogroups) and ends with it in terminate().
  static ChildProcess spawn(const std::string& exe, const std::vector<std::string>& args,
                            const std::map<std::string, std::string>& env, const std::string& logFile,
                            bool newSession = false);
  int wait();        // exit status (128 + signal when killed)
  bool exited();     // whether it has ended (reaped; does not block)
  void terminate();  // SIGTERM (to its process group when it leads a session), then wait
};

// The full path of a program found in PATH (empty: not found).
std::string findProgram(const std::string& name);

}  // namespace wb::app
