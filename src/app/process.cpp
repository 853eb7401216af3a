#include "app/process.h"

#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace wb::app {

std::string selfExecutable() {
  return std::filesystem::read_symlink("/proc/self/exe").string();
}

ChildProcess ChildProcess::spawn(const std::string& exe, const std::vector<std::string>& args,
                                 const std::map<std::string, std::string>& env, const std::string& logFile) {
  ChildProcess c;
  c.pid = fork();
  if (c.pid < 0) throw std::runtime_error("fork failed");
  if (c.pid == 0) {
    for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 1);
    int fd = open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(exe.c_str()));
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  return c;
}

int ChildProcess::wait() {
  if (pid < 0) return -1;
  int status = 0;
  waitpid(pid, &status, 0);
  pid = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void ChildProcess::terminate() {
  if (pid < 0) return;
  kill(pid, SIGTERM);
  wait();
}

}  // namespace wb::app
