#include "app/window/heat_legend.h"

#include <imgui.h>

#include <algorithm>

#include "app/window/number_text.h"
#include "display/display_types.h"
#include "render/path_inspector.h"
#include "shared/heat_ramp.h"

namespace wb::app {
namespace {

ImU32 colour(glm::vec3 c) {
  // The ramp is displayed as stored values (no transfer curve), as the display shader shows it.
  return IM_COL32(int(std::clamp(c.r, 0.0f, 1.0f) * 255.0f + 0.5f),
                  int(std::clamp(c.g, 0.0f, 1.0f) * 255.0f + 0.5f),
                  int(std::clamp(c.b, 0.0f, 1.0f) * 255.0f + 0.5f), 255);
}

}  // namespace

glm::vec3 heatRampColour(float t) {
  return gpu::heatRamp(t);
}

std::optional<HeatLegend> heatLegend(uint32_t view, float maxVertices, const eval::CostSummary* cost) {
  const float vertices = std::max(maxVertices, 1.0f), lastBounce = std::max(maxVertices - 1.0f, 1.0f);
  auto linear = [](float top) {
    return std::vector<std::pair<float, std::string>>{
        {0.0f, "0"}, {0.5f, legendNumber(0.5f * top)}, {1.0f, legendNumber(top)}};
  };
  switch (view) {
    case WB_VIEW_BOUNCES:
      return HeatLegend{"bounces: vertices per path", linear(vertices), ""};
    case WB_VIEW_RR_END:
      return HeatLegend{"rr_end: mean bounce where Russian roulette ended paths (0: camera hit)",
                        linear(lastBounce), "dark purple: no path ended by Russian roulette"};
    case WB_VIEW_VARIANCE:
      // Shown as r / (1 + r): r = 1 (as much noise as signal) is mid-scale.
      return HeatLegend{"variance: relative std dev r of one sample",
                        {{0.0f, "0"}, {0.5f, "1"}, {0.75f, "3"}, {1.0f, "inf"}},
                        ""};
    case WB_VIEW_NAN_SOURCE:
      return HeatLegend{"nan_source: lowest bounce where a sample became NaN/Inf", linear(lastBounce),
                        "elsewhere: the image, dimmed"};
    case WB_VIEW_COST:
    case WB_VIEW_INEFFICIENCY: {
      // Full scale is the 95th percentile over the pixels (the display's costFull / inefficiencyFull).
      if (!cost || !cost->valid()) return std::nullopt;
      const std::string units = eval::clockUnits(cost->clock);
      const bool isCost = view == WB_VIEW_COST;
      const float top = float(isCost ? cost->p95 : cost->inefficiencyP95);
      auto ticks = linear(top);
      ticks.back().second += " (p95)";
      if (isCost)
        return HeatLegend{"cost: " + units + " per sample (" + render::clockName(cost->clock) +
                              " clock, each pixel's " + eval::costEstimateName(cost->estimate) + ")",
                          ticks,
                          cost->lanesIsolated
                              ? "red: the 5% most expensive pixels"
                              : "red: the 5% most expensive; pixels show their subgroup's slowest lane"};
      return HeatLegend{"inefficiency: relative variance x " + units + " per sample (noisy and expensive)",
                        ticks, "red: the 5% least efficient pixels"};
    }
    default:
      return std::nullopt;
  }
}

Rect drawHeatLegend(const HeatLegend& legend, const Rect& image) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const float line = ImGui::GetTextLineHeight(), pad = 6.0f;
  // As wide as its text, within the image (the text wraps in a narrow one).
  const float most = std::max(image.w - 2.0f * pad - 16.0f, 60.0f);
  float width = std::min(
      std::max(ImGui::CalcTextSize(legend.title.c_str()).x, ImGui::CalcTextSize(legend.note.c_str()).x),
      most);
  const float barW = std::min(std::max(width, 120.0f), most), barH = 10.0f;
  width = std::max(width, barW);
  const ImVec2 title = ImGui::CalcTextSize(legend.title.c_str(), nullptr, false, width);
  const ImVec2 note = ImGui::CalcTextSize(legend.note.c_str(), nullptr, false, width);
  const float height = title.y + 4.0f + barH + 2.0f + line + (legend.note.empty() ? 0.0f : note.y + 2.0f);
  // Above the status line, at the image's right edge.
  const ImVec2 a(image.x + image.w - width - 2.0f * pad - 8.0f,
                 image.y + image.h - height - 2.0f * pad - line - 16.0f);
  const ImVec2 b(a.x + width + 2.0f * pad, a.y + height + 2.0f * pad);
  dl->AddRectFilled(a, b, IM_COL32(0, 0, 0, 180), 3.0f);
  const float x0 = a.x + pad;
  float y = a.y + pad;
  dl->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(x0, y), IM_COL32(240, 240, 240, 255),
              legend.title.c_str(), nullptr, width);
  y += title.y + 4.0f;
  constexpr int kSteps = 64;
  for (int i = 0; i < kSteps; ++i) {
    const float t0 = float(i) / kSteps, t1 = float(i + 1) / kSteps;
    dl->AddRectFilled(ImVec2(x0 + t0 * barW, y), ImVec2(x0 + t1 * barW + 0.5f, y + barH),
                      colour(heatRampColour((t0 + t1) * 0.5f)));
  }
  y += barH + 2.0f;
  for (const auto& [t, label] : legend.ticks) {
    const float tw = ImGui::CalcTextSize(label.c_str()).x;
    const float x = std::clamp(x0 + t * barW - tw * 0.5f, x0, x0 + barW - tw);
    dl->AddLine(ImVec2(x0 + t * barW, y - 2.0f - barH * 0.3f), ImVec2(x0 + t * barW, y),
                IM_COL32(255, 255, 255, 200));
    dl->AddText(ImVec2(x, y), IM_COL32(220, 220, 220, 255), label.c_str());
  }
  y += line + 2.0f;
  if (!legend.note.empty())
    dl->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(x0, y), IM_COL32(200, 200, 200, 255),
                legend.note.c_str(), nullptr, width);
  return Rect{a.x, a.y, b.x - a.x, b.y - a.y};
}

}  // namespace wb::app
