// JSON of the cost and debug variants and of per-pass GPU times, as `render --stats`, `bench`, the
// inspector's JSON and the window's --stats write them (stable keys; docs/cost.md).
#pragma once
#include <cstdint>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "eval/cost_map.h"
#include "render/path_inspector.h"
#include "vk/gpu_timer.h"

namespace wb::app {

// {"pass": ms, ...}: each pass's GPU ms per round (a sample or a frame of the render), the median over the
// rounds since the render began; {} without times.
nlohmann::json passMsJson(const vk::GpuTimer* timer);
// The cost summary: clock, units, clocks per sample (mean, p50, p99, max), the frame's clocks, the shares of
// trace calls, shading and raygen, the inefficiency's mean and p99.
nlohmann::json costJson(const eval::CostSummary& s);
// The asserts' failures: how many, and each recorded one with pixel, sample, bounce, stage and label.
nlohmann::json assertsJson(const render::AssertReport& report, const std::map<uint32_t, std::string>& labels);
// One wbPrint record: label, stage, bounce (null before the camera ray), type, value (a number, a bool or an
// array of them).
nlohmann::json printJson(const gpu::PrintRecord& p, const std::map<uint32_t, std::string>& labels);
// A vertex's or sample's bounce as JSON: null for WB_DEBUG_NO_BOUNCE.
nlohmann::json bounceJson(uint32_t bounce);

}  // namespace wb::app
