// A live workbench window under xvfb-run that the test drives as a user does: the window runs on its own
// thread (the real binary, under the validation layer), and the test sends synthetic X input with xdotool to
// the same display while the window's script waits for it (wait_file, wait_clicks), reading where widgets are
// from the stats JSON the script writes.
#pragma once
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"

namespace wb::testing {

// Waits for `p` to exist, at most `seconds`, and no longer than `alive` says the writer runs.
inline bool waitForFile(const std::filesystem::path& p, double seconds,
                        const std::function<bool()>& alive = {}) {
  const auto start = std::chrono::steady_clock::now();
  while (!std::filesystem::exists(p)) {
    if (alive && !alive()) return std::filesystem::exists(p);
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
      return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return true;
}

// The JSON of a file another process writes atomically, once it exists (null after `seconds`).
inline nlohmann::json awaitJson(const std::filesystem::path& p, double seconds = 600) {
  if (!waitForFile(p, seconds)) return nullptr;
  std::ifstream f(p);
  return nlohmann::json::parse(f, nullptr, false);
}

class LiveWindow {
 public:
  // Starts `workbenchArgs` (after the binary) on a fresh virtual display; `dir` holds the display's name
  // and its X authority file.
  LiveWindow(const std::filesystem::path& dir, const std::string& workbenchArgs, const std::string& env = "")
      : dir_(dir) {
    const auto auth = dir / "xauth", displayFile = dir / "display";
    std::filesystem::remove(displayFile);
    const std::string cmd = std::string(kOwnSession) + "env WB_VALIDATION=1 " + env + " " + WB_XVFB_RUN +
                            " -a -f " + auth.string() +
                            " -s '-screen 0 1024x768x24' sh -c 'echo $DISPLAY > " + displayFile.string() +
                            ".tmp && mv " + displayFile.string() + ".tmp " + displayFile.string() +
                            " && exec " + WB_WORKBENCH_BIN + " " + workbenchArgs + "'";
    thread_ = std::thread([this, cmd] {
      result_ = runCommand(cmd);
      exited_ = true;
    });
    if (waitForFile(displayFile, 300)) {
      std::ifstream f(displayFile);
      std::getline(f, display_);
    }
  }
  // A test that ended early (a failed assertion) leaves a script waiting for its signals: Ctrl+Q ends the
  // window instead of the script's wait running out.
  ~LiveWindow() {
    if (!exited_ && !display_.empty()) xdotool("key ctrl+q");
    if (thread_.joinable()) thread_.join();
  }
  LiveWindow(const LiveWindow&) = delete;
  LiveWindow& operator=(const LiveWindow&) = delete;

  // xdotool ARGS on the window's display; its exit status.
  int xdotool(const std::string& args) const {
    return runCommand("env DISPLAY=" + display_ + " XAUTHORITY=" + (dir_ / "xauth").string() + " xdotool " +
                      args)
        .code;
  }
  // The centre of a widget the stats JSON lists (its "widgets" entry: x, y, w, h), as xdotool's "X Y".
  static std::string centre(const nlohmann::json& stats, const std::string& widget) {
    const auto& r = stats["widgets"][widget];
    return std::to_string(int(r[0].get<double>() + r[2].get<double>() / 2)) + " " +
           std::to_string(int(r[1].get<double>() + r[3].get<double>() / 2));
  }
  void signal(const std::string& name) const { std::ofstream(dir_ / name) << "go\n"; }
  // Waits for the window to exit.
  CommandResult finish() {
    if (thread_.joinable()) thread_.join();
    return result_;
  }
  const std::string& display() const { return display_; }
  // awaitJson, giving up as soon as the window has exited (a script that failed writes nothing more).
  nlohmann::json awaitJson(const std::filesystem::path& p, double seconds = 600) const {
    if (!waitForFile(p, seconds, [this] { return !exited_.load(); })) return nullptr;
    std::ifstream f(p);
    return nlohmann::json::parse(f, nullptr, false);
  }

 private:
  std::filesystem::path dir_;
  std::string display_;
  std::thread thread_;
  CommandResult result_;
  std::atomic<bool> exited_{false};
};

}  // namespace wb::testing
