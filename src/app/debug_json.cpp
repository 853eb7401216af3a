#include "app/debug_json.h"

#include <cmath>
#include <cstring>

namespace wb::app {

using nlohmann::json;

json passMsJson(const vk::GpuTimer* timer) {
  json j = json::object();
  if (!timer) return j;
  for (const auto& t : timer->medians()) j[t.pass] = t.ms;
  return j;
}

json costJson(const eval::CostSummary& s) {
  return {{"clock", render::clockName(s.clock)},
          {"units", eval::clockUnits(s.clock)},
          {"pixel_estimate", eval::costEstimateName(s.estimate)},
          {"lanes", s.lanesIsolated ? "isolated" : "shared"},
          {"clocks_per_sample",
           {{"mean", s.mean}, {"p50", s.p50}, {"p95", s.p95}, {"p99", s.p99}, {"max", s.max}}},
          {"frame_clocks", s.frame},
          {"share", {{"trace", s.traceShare}, {"shade", s.shadeShare}, {"raygen", s.raygenShare}}},
          {"inefficiency",
           {{"mean", s.inefficiencyMean}, {"p95", s.inefficiencyP95}, {"p99", s.inefficiencyP99}}}};
}

json bounceJson(uint32_t bounce) {
  return bounce == WB_DEBUG_NO_BOUNCE ? json(nullptr) : json(bounce);
}

json assertsJson(const render::AssertReport& report, const std::map<uint32_t, std::string>& labels) {
  json list = json::array();
  for (const auto& r : report.records) {
    list.push_back({{"pixel", {r.pixel.x, r.pixel.y}},
                    {"sample", r.sampleIndex},
                    {"bounce", bounceJson(r.bounce)},
                    {"stage", render::debugStageName(r.stage)},
                    {"label", render::debugLabelText(r.label, labels)}});
  }
  return {{"failures", report.failures}, {"recorded", report.records.size()}, {"first", list}};
}

json printJson(const gpu::PrintRecord& p, const std::map<uint32_t, std::string>& labels) {
  static const char* kTypes[] = {"float", "int", "uint", "bool"};
  const uint32_t n = std::clamp(p.components, 1u, 4u);
  json values = json::array();
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t bits = p.bits[int(i)];
    if (p.type == WB_PRINT_FLOAT) {
      float f;
      std::memcpy(&f, &bits, sizeof f);
      if (std::isnan(f)) {
        values.push_back("nan");
      } else if (std::isinf(f)) {
        values.push_back(f > 0 ? "inf" : "-inf");
      } else {
        values.push_back(f);
      }
    } else if (p.type == WB_PRINT_INT) {
      values.push_back(int32_t(bits));
    } else if (p.type == WB_PRINT_BOOL) {
      values.push_back(bits != 0);
    } else {
      values.push_back(bits);
    }
  }
  return {{"label", render::debugLabelText(p.label, labels)},
          {"stage", render::debugStageName(p.stage)},
          {"bounce", bounceJson(p.bounce)},
          {"type", p.type < 4 ? kTypes[p.type] : "unknown"},
          {"value", n == 1 ? values[0] : values}};
}

}  // namespace wb::app
