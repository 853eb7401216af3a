// The CPU time of some of this process's threads, from /proc/self/task (Linux). A CPU Vulkan driver
// (lavapipe) runs a device's work on threads it starts with the device: their CPU time tells a shader that
// runs (an endless loop spends it) from one that waits for the CPU (a busy machine starves it).
#pragma once
#include <map>
#include <vector>

namespace wb {

// The ids of this process's threads now (empty where /proc cannot be read).
std::vector<long> threadIds();

// The ids in `now` that are not in `before`: the threads started in between.
std::vector<long> threadsStartedSince(const std::vector<long>& before, const std::vector<long>& now);

// User + system CPU seconds each of `threads` has used so far; a thread that ended is left out.
std::map<long, double> threadCpuSeconds(const std::vector<long>& threads);

// The CPU seconds the threads spent from `since` (an earlier threadCpuSeconds of them) to `now`, each
// thread's difference counted where it is in both.
double cpuSecondsBetween(const std::map<long, double>& since, const std::map<long, double>& now);

}  // namespace wb
