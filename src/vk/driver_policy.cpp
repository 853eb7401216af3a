#include "vk/driver_policy.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "common/env.h"
#include "common/printable.h"

namespace wb::vk {
namespace {

// The CPU share `watch` and the window keep for their frames while a rebuild compiles on a CPU device: enough
// for the window to show the rebuild's progress and take input; what they trace meanwhile is replaced by the
// new pipeline's image anyway.
constexpr double kLoopShareWhileCompiling = 0.1;

double restRatio(double share) {
  return (1.0 - share) / share;
}

}  // namespace

PolicyOverrides PolicyOverrides::fromEnvironment() {
  PolicyOverrides o;
  o.jitWarmup = env::choice("WB_JIT_WARMUP");
  o.pipelineLibraries = env::choice("WB_PIPELINE_LIBRARY");
  if (env::choice("WB_DEFERRED_HOST_OPS") == false) o.deferredHostOps = false;
  o.cpuShapedShaderCode = env::choice("WB_CPU_DEVICE_CODE");
  if (env::choice("WB_SHADER_CLOCK") == false) o.shaderClock = false;
  o.deviceClock = env::choice("WB_DEVICE_CLOCK");
  o.costIsolation = env::choice("WB_COST_ISOLATE");
  o.splitShadows = env::choice("WB_SPLIT_SHADOWS");
  o.splitSlots = env::number("WB_SPLIT_SLOTS");
  o.invocationReorder = env::choice("WB_INVOCATION_REORDER");
  env::checkWorkbenchVariables();  // WB_REBUILD_YIELD's range
  o.rebuildRestRatio = env::number("WB_REBUILD_YIELD");
  o.trialRuns = env::choice("WB_TRIAL_RUN");
  o.hangSeconds = env::number("WB_HANG_SECONDS");
  return o;
}

void checkDriverEnvironment() {
  const auto width = env::get("LP_NATIVE_VECTOR_WIDTH");
  if (!width) return;
  for (const char* accepted : {"128", "256", "512"})
    if (*width == accepted) return;
  throw std::invalid_argument("LP_NATIVE_VECTOR_WIDTH=" + printableExcerpt(*width, 40) +
                              ": llvmpipe (lavapipe) compiles 128, 256 or 512 bits wide; other widths crash "
                              "it (unset it for the workbench's 128)");
}

DevicePolicy resolveDevicePolicy(const DeviceTraits& device, const PolicyOverrides& overrides) {
  const bool cpu = device.cpuImplementation;
  DevicePolicy p;
  p.compilesAtFirstDispatch = cpu;
  p.jitWarmup = overrides.jitWarmup.value_or(cpu);
  p.pipelineLibraries = device.pipelineLibrarySupported && overrides.pipelineLibraries.value_or(!cpu);
  p.deferredHostOps = device.deferredHostOpsSupported && !cpu && overrides.deferredHostOps.value_or(true);
  p.cpuShapedShaderCode = overrides.cpuShapedShaderCode.value_or(cpu);
  if (overrides.rebuildRestRatio) {
    p.watchRestRatio = p.windowRestRatio = std::max(0.0, *overrides.rebuildRestRatio);
  } else if (cpu) {
    p.watchRestRatio = p.windowRestRatio = restRatio(kLoopShareWhileCompiling);
  }
  p.windowTraceShareWhileCompiling = cpu ? kLoopShareWhileCompiling : 1.0;
  p.trialRuns = overrides.trialRuns.value_or(true);
  if (overrides.hangSeconds) p.hangSeconds = *overrides.hangSeconds;
  p.hangCountsDriverCpu = cpu;
  p.shaderClock = device.shaderClockSupported && overrides.shaderClock.value_or(true);
  p.deviceClock = overrides.deviceClock.value_or(false);
  p.costIsolatesLanes = device.raygenSubgroupVote && overrides.costIsolation.value_or(true);
  p.costByMedian = cpu;
  p.splitShadows = overrides.splitShadows.value_or(!cpu);
  if (overrides.splitSlots) p.splitSlotsLimit = uint32_t(*overrides.splitSlots);
  p.invocationReorder = device.invocationReorderSupported &&
                        overrides.invocationReorder.value_or(device.invocationReorderReorders);
  return p;
}

std::vector<std::string> applyDriverDefaults(const std::filesystem::path& cacheDir) {
  checkDriverEnvironment();
  static const std::vector<std::string> applied = [&] {
    std::vector<std::string> set;
    auto setDefault = [&](const char* name, const std::string& value) {
      env::set(name, value);  // unset or empty: ours to set
      set.push_back(std::string(name) + "=" + value);
    };
    const bool usersCache = env::get("MESA_SHADER_CACHE_DIR").has_value();
    if (!env::get("LP_NATIVE_VECTOR_WIDTH") && !usersCache) setDefault("LP_NATIVE_VECTOR_WIDTH", "128");
    if (!usersCache) {  // the width is set by now: the user's or ours
      std::string folder = "lp";
      for (char c : env::get("LP_NATIVE_VECTOR_WIDTH").value_or(""))
        folder += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      setDefault("MESA_SHADER_CACHE_DIR", (cacheDir / "mesa" / folder).string());
    }
    return set;
  }();
  return applied;
}

}  // namespace wb::vk
