#include "vk/device_select.h"

#include <algorithm>
#include <cctype>
#include <vulkan/vulkan.h>

namespace wb::vk {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::vector<std::string> missingExtensions(const DeviceCandidate& c,
                                           const std::vector<std::string>& required) {
  std::vector<std::string> missing;
  for (const auto& r : required) {
    if (std::find(c.extensions.begin(), c.extensions.end(), r) == c.extensions.end()) missing.push_back(r);
  }
  return missing;
}

std::string versionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v));
}

int rank(const DeviceCandidate& c) {
  return c.discrete ? 3 : c.integrated ? 2 : c.cpu ? 0 : 1;
}

}  // namespace

const std::vector<std::string>& requiredDeviceExtensions() {
  static const std::vector<std::string> ext = {
      "VK_KHR_acceleration_structure",
      "VK_KHR_ray_tracing_pipeline",
      "VK_KHR_deferred_host_operations",
  };
  return ext;
}

DeviceChoice chooseDevice(const std::vector<DeviceCandidate>& candidates,
                          const std::vector<std::string>& required, const std::string& nameOverride) {
  DeviceChoice choice;
  std::string report;
  std::optional<size_t> best;
  bool overrideMatched = false;
  for (size_t i = 0; i < candidates.size(); ++i) {
    const auto& c = candidates[i];
    auto missing = missingExtensions(c, required);
    bool oldApi = c.apiVersion < VK_API_VERSION_1_3;
    if (!report.empty()) report += "; ";
    report += "'" + c.name + "'";
    const bool qualifies = missing.empty() && !oldApi && c.missingFeatures.empty();
    if (qualifies) {
      report += " (qualifies)";
    } else {
      report += " lacks";
      if (oldApi) report += " Vulkan 1.3 (has " + versionString(c.apiVersion) + ")";
      for (const auto& m : missing) report += " " + m;
      for (const auto& f : c.missingFeatures) report += " feature " + f;
    }
    bool nameOk = nameOverride.empty() || lower(c.name).find(lower(nameOverride)) != std::string::npos;
    overrideMatched = overrideMatched || (!nameOverride.empty() && nameOk);
    if (!qualifies || !nameOk) continue;
    if (!best || rank(c) > rank(candidates[*best])) best = i;
  }
  if (best) {
    choice.index = best;
    return choice;
  }
  if (candidates.empty()) {
    choice.error =
        "no Vulkan devices found (is a Vulkan driver installed? lavapipe: mesa-vulkan-drivers >= 24.1)";
  } else if (!nameOverride.empty() && !overrideMatched) {
    choice.error = "no device matches --device '" + nameOverride + "'; devices found: " + report;
  } else {
    choice.error =
        "no device supports Vulkan ray tracing; devices found: " + report +
        " (lavapipe needs Mesa >= 24.1: run scripts/setup.sh to install it from bookworm-backports)";
  }
  return choice;
}

}  // namespace wb::vk
