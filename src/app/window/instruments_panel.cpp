#include "app/window/instruments_panel.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <imgui.h>

#include "display/display_types.h"

namespace wb::app {
namespace {

// Failures listed in the panel (all of them are marked on the image).
constexpr size_t kAssertsListed = 8;

std::string bounceText(uint32_t bounce) {
  return bounce == WB_DEBUG_NO_BOUNCE ? "-" : std::to_string(bounce);
}

}  // namespace

void drawPassTimes(const live::LiveSession& session, double displayMs) {
  const auto& in = session.instruments();
  const auto& times = in.passTimes();
  if (times.empty()) {
    ImGui::TextDisabled("GPU time per pass: no timestamps yet");
    return;
  }
  const auto denoiseMs = in.denoiseMs();  // its last run, while denoising
  double total = displayMs + denoiseMs.value_or(0.0);
  for (const auto& t : times) total += t.ms;
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (ImGui::BeginTable("pass_ms", 3, flags)) {
    ImGui::TableSetupColumn("pass");
    ImGui::TableSetupColumn("GPU ms");
    ImGui::TableSetupColumn("share");
    ImGui::TableHeadersRow();
    auto row = [&](const char* name, double ms, uint32_t scopes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      if (scopes > 1) {
        ImGui::Text("%s (%u)", name, scopes);  // strips of one frame
      } else {
        ImGui::TextUnformatted(name);
      }
      ImGui::TableNextColumn();
      ImGui::Text("%.3f", ms);
      ImGui::TableNextColumn();
      ImGui::Text("%.0f%%", total > 0 ? 100.0 * ms / total : 0.0);
    };
    for (const auto& t : times) row(t.pass.c_str(), t.ms, t.scopes);
    if (denoiseMs) row("denoise (last run)", *denoiseMs, 1);
    row("display", displayMs, 1);
    ImGui::EndTable();
  }
  const std::vector<float> history(in.passHistory().begin(), in.passHistory().end());
  const float top = history.empty() ? 1.0f : *std::max_element(history.begin(), history.end());
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "GPU ms per submission (max %.1f)", top);
  ImGui::PlotLines("##pass_history", history.data(), int(history.size()), 0, overlay, 0.0f,
                   std::max(top * 1.1f, 0.1f), ImVec2(ImGui::GetContentRegionAvail().x, 50));
}

void drawCostSummary(const live::LiveSession& session) {
  const uint32_t view = session.state().params.display.view;
  if (view != WB_VIEW_COST && view != WB_VIEW_INEFFICIENCY) return;
  const auto& tracer = session.render().pathTracer();
  if (tracer.clock() == WB_CLOCK_NONE) {
    ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1.0f),
                       "no shader clock on this device (VK_KHR_shader_clock, or WB_SHADER_CLOCK=0): no cost "
                       "data, the image is shown dimmed");
    return;
  }
  const auto& cost = session.instruments().cost();
  if (!cost || !cost->valid()) {
    ImGui::TextDisabled("cost variant: waiting for the first samples");
    return;
  }
  // The colour bar is over the image (heat_legend.h); here the numbers behind it.
  const auto& c = *cost;
  const std::string units = eval::clockUnits(c.clock);
  if (view == WB_VIEW_COST) {
    ImGui::TextWrapped("%s per sample (%s clock, each pixel's %s)", units.c_str(), render::clockName(c.clock),
                       eval::costEstimateName(c.estimate));
    // A pixel at full scale: its share of the frame's clocks, and against the mean pixel.
    ImGui::TextWrapped("full scale: %.2fx the mean pixel, %.3g%% of the frame's clocks",
                       c.mean > 0 ? c.p95 / c.mean : 0.0, 100.0 * c.p95 / c.frame);
    ImGui::TextWrapped("mean %.4g  p50 %.4g  p99 %.4g  max %.4g", c.mean, c.p50, c.p99, c.max);
    ImGui::TextWrapped("frame: trace calls %.0f%%, shading %.0f%%, raygen %.0f%%", 100.0 * c.traceShare,
                       100.0 * c.shadeShare, 100.0 * c.raygenShare);
  } else {
    ImGui::TextWrapped("relative variance x %s per sample (1 / efficiency: noisy and expensive)",
                       units.c_str());
    ImGui::Text("full scale (p95) %.4g  mean %.4g  p99 %.4g", c.inefficiencyP95, c.inefficiencyMean,
                c.inefficiencyP99);
  }
}

void drawAssertsSection(live::LiveSession& session) {
  auto& st = session.state();
  if (session.mode() != render::RenderMode::PathTrace) return;
  ImGui::Checkbox("check wbAssert (asserts variant)", &st.asserts);
  if (!st.asserts) return;
  const auto& report = session.instruments().asserts();
  if (report.failures == 0) {
    ImGui::TextDisabled("no wbAssert failed since the accumulation restarted");
    return;
  }
  ImGui::TextColored(ImVec4(1.0f, 0.3f, 1.0f, 1.0f), "%u failures (%zu recorded, marked on the image)",
                     report.failures, report.records.size());
  const auto& labels = session.instruments().labels();
  for (size_t i = 0; i < std::min(report.records.size(), kAssertsListed); ++i) {
    const auto& r = report.records[i];
    ImGui::Text("'%s' at %u,%u sample %u bounce %s (%s)", render::debugLabelText(r.label, labels).c_str(),
                r.pixel.x, r.pixel.y, r.sampleIndex, bounceText(r.bounce).c_str(),
                render::debugStageName(r.stage));
  }
}

void drawPrintsSection(const live::LiveSession& session) {
  const auto& st = session.state();
  if (!st.inspectPixel || session.mode() != render::RenderMode::PathTrace) return;
  const render::InspectedSample* s = session.inspection().shown(st.inspectShown);
  if (!s) return;
  const uint32_t made = s->record.prints;
  if (made == 0) {
    ImGui::TextDisabled("no wbPrint in this sample");
    return;
  }
  ImGui::Text("wbPrint: %u%s", made, made > s->prints.size() ? " (the first ones kept)" : "");
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders |
                                ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollY;
  const float height =
      std::min(10.0f, float(s->prints.size()) + 1.5f) * ImGui::GetTextLineHeightWithSpacing();
  if (!ImGui::BeginTable("inspect_prints", 4, flags, ImVec2(0.0f, height))) return;
  for (const char* h : {"#", "stage", "label", "value"}) ImGui::TableSetupColumn(h);
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableHeadersRow();
  const auto& labels = session.instruments().labels();
  for (const auto& p : s->prints) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(bounceText(p.bounce).c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(render::debugStageName(p.stage));
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(render::debugLabelText(p.label, labels).c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(render::printValueText(p).c_str());
  }
  ImGui::EndTable();
}

void drawAssertMarks(const live::LiveSession& session, const Rect& image) {
  if (!session.state().asserts || session.mode() != render::RenderMode::PathTrace) return;
  const auto& records = session.instruments().asserts().records;
  const uint32_t w = session.imageWidth(), h = session.imageHeight();
  if (records.empty() || w == 0 || h == 0) return;
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->PushClipRect(ImVec2(image.x, image.y), ImVec2(image.x + image.w, image.y + image.h), true);
  const float sx = image.w / float(w), sy = image.h / float(h);
  for (const auto& r : records) {
    if (r.pixel.x >= w || r.pixel.y >= h) continue;
    const ImVec2 a(image.x + float(r.pixel.x) * sx, image.y + float(r.pixel.y) * sy);
    dl->AddRect(ImVec2(a.x - 1, a.y - 1), ImVec2(a.x + std::max(sx, 1.0f) + 1, a.y + std::max(sy, 1.0f) + 1),
                IM_COL32(255, 0, 255, 255));
  }
  dl->PopClipRect();
}

}  // namespace wb::app
