#include "common/thread_cpu.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

namespace wb {

std::vector<long> threadIds() {
  std::vector<long> ids;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator("/proc/self/task", ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    char* end = nullptr;
    const std::string name = it->path().filename().string();
    const long id = std::strtol(name.c_str(), &end, 10);
    if (end && *end == '\0' && id > 0) ids.push_back(id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<long> threadsStartedSince(const std::vector<long>& before, const std::vector<long>& now) {
  std::vector<long> sortedBefore = before, started;
  std::sort(sortedBefore.begin(), sortedBefore.end());
  for (long id : now)
    if (!std::binary_search(sortedBefore.begin(), sortedBefore.end(), id)) started.push_back(id);
  return started;
}

std::map<long, double> threadCpuSeconds(const std::vector<long>& threads) {
  static const double ticksPerSecond = double(std::max(1L, ::sysconf(_SC_CLK_TCK)));
  std::map<long, double> seconds;
  for (long id : threads) {
    std::ifstream in("/proc/self/task/" + std::to_string(id) + "/stat");
    const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Fields after the command name (in parentheses, which may hold spaces): state is field 3, utime 14,
    // stime 15 (proc(5)).
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;  // the thread ended
    std::istringstream fields(stat.substr(close + 1));
    std::string field;
    unsigned long long utime = 0, stime = 0;
    for (int k = 3; k <= 15 && fields >> field; ++k) {
      if (k == 14) utime = std::strtoull(field.c_str(), nullptr, 10);
      if (k == 15) stime = std::strtoull(field.c_str(), nullptr, 10);
    }
    seconds[id] = double(utime + stime) / ticksPerSecond;
  }
  return seconds;
}

double cpuSecondsBetween(const std::map<long, double>& since, const std::map<long, double>& now) {
  double total = 0;
  for (const auto& [id, s] : now) {
    const auto it = since.find(id);
    if (it != since.end()) total += std::max(0.0, s - it->second);
  }
  return total;
}

}  // namespace wb
