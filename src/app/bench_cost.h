// `bench --only cost`: what the path tracer's measuring variants cost when on, on this device: seconds per
// sample of the default, cost, inspecting and asserts variants of the default scene (alternated, medians),
// their overhead against the default, each variant's GPU time per pass, and the cost map's summary.
#pragma once
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace wb::app {

nlohmann::json benchCostVariants(uint32_t width, uint32_t height, uint32_t spp, int repeats,
                                 const std::string& device, std::string& deviceName, std::string& driver);

}  // namespace wb::app
