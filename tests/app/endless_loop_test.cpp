// A shader that never returns costs one edit, not the session: under `watch` the new pipeline's trial frame
// on the second device does not finish, the reload is refused with the file and the reason (log line and
// stderr), the last good pipeline keeps rendering, the next good edit is installed, and SIGTERM then ends the
// process. Each wait has a limit the test enforces itself (generous: a busy machine is slow, never hung).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"
#include "../common/watch_log.h"
#include "common/paths.h"

namespace fs = std::filesystem;
using wb::testing::readFile;
using wb::testing::writeFile;

namespace {

constexpr double kEventCapSeconds = 300;

// closesthit.rchit with a loop at its start that never ends (it has side effects, so no compiler may drop
// it).
std::string withEndlessLoop(std::string text) {
  const auto main = text.find("void main()");
  const auto body = text.find('{', main) + 1;
  text.insert(body, "\n  while (payload.radiance.x >= 0.0) { payload.radiance.x += 1.0; }\n");
  return text;
}

bool exitedWithin(pid_t pid, double seconds, int& status) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (waitpid(pid, &status, WNOHANG) == pid) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// `workbench watch --headless` on a copy of the project's shaders and assets under `root`, with
// WB_HANG_SECONDS=3 (and WB_TRIAL_RUN=0 when `trialRuns` is false); killed with its process group when the
// test ends. ready() waits until it watches.
struct WatchSession {
  fs::path root, log, out;
  pid_t pid = -1;

  WatchSession(const std::string& name, bool trialRuns)
      : root(fs::temp_directory_path() / (name + std::to_string(::getpid()))),
        log(root / "reloads.jsonl"),
        out(root / "watch.out") {
    fs::remove_all(root);
    fs::create_directories(root / "shader_cache");
    fs::copy(wb::projectRoot() / "shaders", root / "shaders", fs::copy_options::recursive);
    fs::copy(wb::projectRoot() / "assets", root / "assets", fs::copy_options::recursive);
    pid = fork();
    if (pid == 0) {
      setsid();
      FILE* o = std::freopen(out.c_str(), "w", stdout);
      (void)o;
      dup2(fileno(stdout), fileno(stderr));
      ::setenv("WB_ROOT", root.c_str(), 1);
      ::setenv("WB_HANG_SECONDS", "3", 1);
      if (!trialRuns) ::setenv("WB_TRIAL_RUN", "0", 1);
      execl(WB_WORKBENCH_BIN, WB_WORKBENCH_BIN, "watch", "--headless", "--size", "32x32", "--log",
            log.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  ~WatchSession() {
    int status = 0;
    if (pid > 0 && waitpid(pid, &status, WNOHANG) == 0) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
    }
    fs::remove_all(root);
  }
  bool ready() const {
    const auto started = std::chrono::steady_clock::now();
    while (readFile(out).find("watching") == std::string::npos &&
           std::chrono::steady_clock::now() - started < std::chrono::seconds(int(kEventCapSeconds)))
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return readFile(out).find("watching") != std::string::npos;
  }
};

}  // namespace

TEST(EndlessLoop, WatchRefusesTheEditKeepsRenderingAndEndsOnSigterm) {
  WatchSession w("wb_endless_", true);
  ASSERT_GT(w.pid, 0);
  ASSERT_TRUE(w.ready()) << readFile(w.out);
  const fs::path &root = w.root, &log = w.log, &out = w.out;
  const pid_t pid = w.pid;

  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  const std::string good = readFile(chit);
  writeFile(chit, withEndlessLoop(good));
  auto lines = wb::testing::waitForLog(log, 1, kEventCapSeconds);
  ASSERT_EQ(lines.size(), 1u) << readFile(out);
  EXPECT_FALSE(lines[0]["ok"].get<bool>()) << lines[0].dump();
  EXPECT_TRUE(lines[0]["pipelines_rebuilt"].empty()) << "the hanging pipeline was installed";
  const std::string error = lines[0]["error"].get<std::string>();
  EXPECT_NE(error.find("closesthit.rchit"), std::string::npos) << error;
  EXPECT_NE(error.find("did not finish"), std::string::npos) << error;
  EXPECT_NE(error.find("endless loop"), std::string::npos) << error;
  EXPECT_NE(readFile(out).find("endless loop"), std::string::npos) << "not said on the terminal";
  // On a CPU device (lavapipe) the trial counted as hung once its driver threads had spent the limit in CPU
  // time too (a starved warm-up is waited for): the message says how much they spent, at least the limit.
  if (readFile(out).find(" on llvmpipe") != std::string::npos) {
    const auto cpuAt = error.find(" s of CPU");
    ASSERT_NE(cpuAt, std::string::npos) << error;
    const auto numberAt = error.rfind(' ', cpuAt - 1) + 1;
    const double cpu = std::stod(error.substr(numberAt, cpuAt - numberAt));
    const auto limitAt = error.find("trial frame in ") + std::string("trial frame in ").size();
    const double limit = std::stod(error.substr(limitAt));
    EXPECT_GE(limit, 3.0) << error;
    EXPECT_GE(cpu, limit) << error;
  }

  // The session goes on: a good edit is installed and drawn.
  std::string edited = good;
  const std::string needle = "const float minCos = 1e-3;";
  ASSERT_NE(edited.find(needle), std::string::npos);
  edited.replace(edited.find(needle), needle.size(), "const float minCos = 1.0001e-3;");
  writeFile(chit, edited);
  lines = wb::testing::waitForLog(log, 2, kEventCapSeconds);
  ASSERT_EQ(lines.size(), 2u) << readFile(out);
  EXPECT_TRUE(lines[1]["ok"].get<bool>()) << lines[1].dump();
  EXPECT_EQ(lines[1]["pipelines_rebuilt"], nlohmann::json::array({"pathtracer"})) << lines[1].dump();
  EXPECT_TRUE(lines[1]["edit_to_first_frame_ms"].is_number()) << "the new pipeline never drew a frame";

  // SIGTERM ends it as Ctrl-C does (status 0), although a device of the process is still busy for good.
  kill(pid, SIGTERM);
  int status = 0;
  ASSERT_TRUE(exitedWithin(pid, 60, status)) << "watch did not end after SIGTERM:\n" << readFile(out);
  ASSERT_TRUE(WIFEXITED(status)) << readFile(out);
  EXPECT_EQ(WEXITSTATUS(status), 0) << readFile(out);
}

// Without the trial frame the render device itself runs the endless loop: the frame watchdog says which edit
// did it (log line and stderr) and ends the process with status 4 (no driver here stops a running shader).
TEST(EndlessLoop, TheRenderDevicesWatchdogSaysWhichEditHungAndEnds) {
  WatchSession w("wb_endless_main_", false);
  ASSERT_GT(w.pid, 0);
  ASSERT_TRUE(w.ready()) << readFile(w.out);
  const fs::path &root = w.root, &log = w.log, &out = w.out;
  const pid_t pid = w.pid;
  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  writeFile(chit, withEndlessLoop(readFile(chit)));
  int status = 0;
  ASSERT_TRUE(exitedWithin(pid, kEventCapSeconds, status)) << "watch hung for good:\n" << readFile(out);
  ASSERT_TRUE(WIFEXITED(status)) << readFile(out);
  EXPECT_EQ(WEXITSTATUS(status), 4) << readFile(out);
  const auto lines = wb::testing::readLog(log);
  ASSERT_FALSE(lines.empty()) << "no log line says which edit hung:\n" << readFile(out);
  const std::string error = lines.back()["error"].get<std::string>();
  EXPECT_FALSE(lines.back()["ok"].get<bool>());
  EXPECT_NE(error.find("closesthit.rchit"), std::string::npos) << error;
  EXPECT_NE(error.find("endless loop"), std::string::npos) << error;
  EXPECT_NE(readFile(out).find("endless loop"), std::string::npos) << "not said on the terminal";
}
