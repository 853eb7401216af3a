#include "common/env.h"

#include <cstdlib>
#include <stdexcept>

#include "common/numbers.h"
#include "common/printable.h"

namespace wb::env {
namespace {

std::string shown(const std::string& value) {
  return printableExcerpt(value, 60);
}

// The WB_* switches (0 or 1) the workbench reads.
constexpr const char* kSwitches[] = {
    "WB_PIPELINE_LIBRARY", "WB_DEFERRED_HOST_OPS",   "WB_JIT_WARMUP",         "WB_TRIAL_RUN",
    "WB_CPU_DEVICE_CODE",  "WB_SIMULATE_NO_PRESENT", "WB_SIMULATE_DISK_FULL", "WB_VALIDATION",
    "WB_SHADER_CLOCK",     "WB_DEVICE_CLOCK",        "WB_COST_ISOLATE",       "WB_DENOISE_WINDOW",
    "WB_SPLIT_SHADOWS",    "WB_INVOCATION_REORDER"};

// WB_REBUILD_YIELD: frame times of rest per frame while a rebuild compiles.
constexpr double kMaxRebuildYield = 1000.0;
// WB_HANG_SECONDS: the shortest wait for a frame before it counts as hung.
constexpr double kMinHangSeconds = 0.5, kMaxHangSeconds = 3600.0;
// WB_SPLIT_SLOTS: the most shadow requests a sample leaves for the split's shadow launch.
constexpr double kMaxSplitSlots = 18.0;

}  // namespace

std::optional<std::string> get(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) return std::nullopt;
  return std::string(v);
}

std::optional<bool> choice(const char* name) {
  const auto v = get(name);
  if (!v) return std::nullopt;
  if (*v == "1") return true;
  if (*v == "0") return false;
  throw std::invalid_argument(std::string(name) + "=" + shown(*v) + ": expected 0 or 1 (or unset)");
}

bool enabled(const char* name) {
  return choice(name).value_or(false);
}

std::optional<double> number(const char* name) {
  const auto v = get(name);
  if (!v) return std::nullopt;
  const auto d = parseDecimal(*v);
  if (!d) throw std::invalid_argument(std::string(name) + "=" + shown(*v) + ": expected a decimal number");
  return d;
}

void set(const char* name, const std::string& value) {
  ::setenv(name, value.c_str(), 1);
}

void checkWorkbenchVariables() {
  for (const char* name : kSwitches) choice(name);
  if (const auto yield = number("WB_REBUILD_YIELD"); yield && (*yield < 0 || *yield > kMaxRebuildYield)) {
    throw std::invalid_argument("WB_REBUILD_YIELD=" + shown(*get("WB_REBUILD_YIELD")) +
                                ": expected frame times of rest from 0 to " +
                                std::to_string(int(kMaxRebuildYield)));
  }
  if (const auto hang = number("WB_HANG_SECONDS");
      hang && (*hang < kMinHangSeconds || *hang > kMaxHangSeconds)) {
    throw std::invalid_argument("WB_HANG_SECONDS=" + shown(*get("WB_HANG_SECONDS")) +
                                ": expected seconds from 0.5 to 3600");
  }
  if (const auto slots = number("WB_SPLIT_SLOTS");
      slots && (*slots < 0 || *slots > kMaxSplitSlots || *slots != double(int(*slots)))) {
    throw std::invalid_argument("WB_SPLIT_SLOTS=" + shown(*get("WB_SPLIT_SLOTS")) +
                                ": expected a whole number of requests from 0 to 18");
  }
}

}  // namespace wb::env
