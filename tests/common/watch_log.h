// Files and `watch --log` lines for the tests that drive `workbench watch`: reading and writing whole files,
// and waiting for reload lines with a generous cap (a busy machine makes a reload take tens of seconds),
// never for a fixed time.
#pragma once
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

namespace wb::testing {

inline std::string readFile(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void writeFile(const std::filesystem::path& p, const std::string& text) {
  std::ofstream f(p, std::ios::trunc);
  f << text;
}

// The JSON lines of a reload log (blank lines skipped).
inline std::vector<nlohmann::json> readLog(const std::filesystem::path& p) {
  std::vector<nlohmann::json> lines;
  std::ifstream f(p);
  std::string line;
  while (std::getline(f, line)) {
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  }
  return lines;
}

// Waits until the log has `n` lines, or `seconds` pass; returns what it has.
inline std::vector<nlohmann::json> waitForLog(const std::filesystem::path& p, size_t n, double seconds) {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    auto lines = readLog(p);
    if (lines.size() >= n) return lines;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
      return lines;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

}  // namespace wb::testing
