#include "app/process.h"

#include <algorithm>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <spawn.h>
#include <filesystem>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include "common/env.h"

extern char** environ;

namespace wb::app {

std::string selfExecutable() {
  return std::filesystem::read_symlink("/proc/self/exe").string();
}

// posix_spawn, not fork + setenv: the parent has threads (Vulkan's, hot reload's), and only
// async-signal-safe calls are allowed between fork and exec; the child's environment is built here instead.
ChildProcess ChildProcess::spawn(const std::string& exe, const std::vector<std::string>& args,
                                 const std::map<std::string, std::string>& env, const std::string& logFile,
                                 bool newSession) {
  std::vector<std::string> envStrings;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    if (!env.count(entry.substr(0, entry.find('=')))) envStrings.push_back(entry);
  }
  for (const auto& [k, v] : env) envStrings.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (auto& s : envStrings) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> argStrings = {exe};
  argStrings.insert(argStrings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argStrings) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  if (newSession) posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSID);
  ChildProcess c;
  c.ownSession = newSession;
  const int rc = posix_spawnp(&c.pid, exe.c_str(), &actions, &attr, argv.data(), envp.data());
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    c.pid = -1;
    throw std::runtime_error("cannot start " + exe + ": " + std::strerror(rc));
  }
  return c;
}

int ChildProcess::wait() {
  if (pid < 0) return exitStatus;
  int status = 0;
  waitpid(pid, &status, 0);
  pid = -1;
  exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return exitStatus;
}

bool ChildProcess::exited() {
  if (pid < 0) return true;
  int status = 0;
  if (waitpid(pid, &status, WNOHANG) != pid) return false;
  pid = -1;
  exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return true;
}

void ChildProcess::terminate() {
  if (pid < 0) return;
  kill(ownSession ? -pid : pid, SIGTERM);
  wait();
}

std::string findProgram(const std::string& name) {
  const std::string dirs = env::get("PATH").value_or("/usr/bin:/bin");
  for (size_t start = 0; start <= dirs.size();) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::filesystem::path candidate = std::filesystem::path(dirs.substr(start, end - start)) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return {};
}

}  // namespace wb::app
