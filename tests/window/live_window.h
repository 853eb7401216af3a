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
#include <iostream>
#include <iterator>
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

// The JSON object in a file another process writes, once it exists and holds one: null after `seconds`, or as
// soon as `alive` says the writer has ended without writing it. A file that does not parse (yet) is read
// again until then; a failure says on stderr what the file held, or that it never appeared.
inline nlohmann::json awaitJson(const std::filesystem::path& p, double seconds = 600,
                                const std::function<bool()>& alive = {}) {
  const auto start = std::chrono::steady_clock::now();
  std::string text;
  bool seen = false;
  for (;;) {
    // Both before reading: a writer that ended has written all it will, and a file there when the time is up
    // (after a stall of the whole machine too) is still read.
    const bool ended = alive && !alive();
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (std::filesystem::exists(p)) {
      seen = true;
      std::ifstream f(p);
      text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
      auto j = nlohmann::json::parse(text, nullptr, false);
      if (j.is_object()) return j;
    }
    if (ended || waited > seconds) {
      std::cerr << "awaitJson: " << p.string() << (seen ? " holds no JSON object" : " does not exist")
                << " after " << waited << " s" << (ended ? " (its writer has ended)" : "")
                << (seen ? ": '" + text.substr(0, 400) + "'" : std::string()) << "\n";
      return nullptr;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
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
  // Ends the window now (Ctrl+Q, as a user would) and waits for it: what a failed assertion prints, without
  // waiting for the script's own time limits to run out.
  CommandResult stop() {
    if (!exited_ && !display_.empty()) xdotool("key ctrl+q");
    return finish();
  }
  const std::string& display() const { return display_; }
  // awaitJson, giving up as soon as the window has exited (a script that failed writes nothing more).
  nlohmann::json awaitJson(const std::filesystem::path& p, double seconds = 600) const {
    return wb::testing::awaitJson(p, seconds, [this] { return !exited_.load(); });
  }

 private:
  std::filesystem::path dir_;
  std::string display_;
  std::thread thread_;
  CommandResult result_;
  std::atomic<bool> exited_{false};
};

}  // namespace wb::testing
