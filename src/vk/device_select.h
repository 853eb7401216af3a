// Choosing a physical device: pure logic over device descriptions, so it is testable without a GPU.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace wb::vk {

struct DeviceCandidate {
  std::string name;
  bool discrete = false;
  bool integrated = false;
  bool cpu = false;
  uint32_t apiVersion = 0;
  std::vector<std::string> extensions;
  std::vector<std::string> missingFeatures;  // device features the workbench needs that this one lacks
};

struct DeviceChoice {
  std::optional<size_t> index;  // chosen candidate
  std::string error;            // why none qualified (names every device and what it lacks)
};

// Extensions a device needs for the workbench's ray tracing pipelines.
const std::vector<std::string>& requiredDeviceExtensions();

// Picks the best qualifying device: a name override (substring, case-insensitive) first, else discrete GPU,
// else integrated, else anything else (lavapipe). Devices missing an extension, a feature or Vulkan 1.3 never
// qualify (so a GPU without, say, dynamic rendering falls back to lavapipe instead of failing).
DeviceChoice chooseDevice(const std::vector<DeviceCandidate>& candidates,
                          const std::vector<std::string>& required, const std::string& nameOverride = "");

}  // namespace wb::vk
