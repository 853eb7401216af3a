// What the tests that run real sweeps share: the workbench's `sweep` command, a small sweep file, waiting for
// a sweep's tasks, and comparing two sweeps' outputs.
#pragma once
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"

namespace wb::testing {

namespace fs = std::filesystem;

inline CommandResult sweep(const std::string& args) {
  return runCommand(std::string(WB_WORKBENCH_BIN) + " sweep " + args);
}

inline fs::path sweepTempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("wb_sweep_cli_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline std::string fileText(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

inline nlohmann::json sweepStatus(const fs::path& dir) {
  const CommandResult r =
      runCommand(std::string(WB_WORKBENCH_BIN) + " sweep status --json " + dir.string(), false);
  EXPECT_EQ(r.code, 0) << r.output;
  try {
    return nlohmann::json::parse(r.output);
  } catch (const nlohmann::json::exception&) {
    ADD_FAILURE() << "status --json is not JSON: " << r.output;
    return nlohmann::json::object();
  }
}

// Polls `done` every half second for up to `seconds` (generous: a busy machine is slow, not wrong).
inline bool waitFor(const std::function<bool()>& done, double seconds = 900) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  return done();
}

// A CSV without the columns whose header names one of `drop`.
inline std::string csvWithout(const fs::path& p, const std::vector<std::string>& drop) {
  std::istringstream in(fileText(p));
  std::string out, line;
  std::vector<bool> keep;
  while (std::getline(in, line)) {
    std::vector<std::string> cols;
    std::string cur;
    bool quoted = false;
    for (char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) {
        cols.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    cols.push_back(cur);
    if (keep.empty())
      for (const auto& h : cols) keep.push_back(std::find(drop.begin(), drop.end(), h) == drop.end());
    for (size_t i = 0; i < cols.size(); ++i)
      if (i >= keep.size() || keep[i]) out += cols[i] + ",";
    out += "\n";
  }
  return out;
}

// Every file below `dir` whose name ends in `suffix`, relative to `dir`, sorted.
inline std::vector<std::string> filesEndingIn(const fs::path& dir, const std::string& suffix) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.size() >= suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace wb::testing
