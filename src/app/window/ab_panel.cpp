#include "app/window/ab_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/window/widget_rects.h"

namespace wb::app {

namespace {

// The image as coloured rectangles (one per pixel of the small A/B image), `split` = the column where the
// second image starts (width: only the first).
void drawPixels(ImDrawList* dl, ImVec2 at, float size, uint32_t w, uint32_t h,
                const std::vector<uint8_t>& first, const std::vector<uint8_t>& second, uint32_t split) {
  const float px = size / float(std::max(w, h));
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const uint8_t* p = &(x < split ? first : second)[(size_t(y) * w + x) * 4];
      const ImVec2 a(at.x + float(x) * px, at.y + float(y) * px);
      dl->AddRectFilled(a, ImVec2(a.x + px, a.y + px), IM_COL32(p[0], p[1], p[2], 255));
    }
  }
}

}  // namespace

void drawABPanel(live::ABState& v, const std::string& mode, float viewRight, float viewBottom) {
  if (!v.open || (v.results.empty() && v.note.empty())) return;
  const float panelW = 300;
  ImGui::SetNextWindowPos(ImVec2(viewRight - panelW - 10, viewBottom - 40), ImGuiCond_FirstUseEver,
                          ImVec2(0, 1));
  ImGui::SetNextWindowSize(ImVec2(panelW, 0), ImGuiCond_FirstUseEver);
  const bool expanded = ImGui::Begin("A/B: old vs new", &v.open);
  {
    // The panel and its title bar's close button (the rightmost square of the title bar).
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    const ImVec2 pad = ImGui::GetStyle().FramePadding;
    const float button = ImGui::GetFontSize() + 2.0f * pad.x, title = ImGui::GetFontSize() + 2.0f * pad.y;
    widgetRects().note("ab_panel", Rect{pos.x, pos.y, size.x, size.y});
    widgetRects().note("ab.close", Rect{pos.x + size.x - button, pos.y, button, title});
  }
  if (!expanded) {  // collapsed
    ImGui::End();
    return;
  }
  ImGui::Checkbox("compare after each edit", &v.enabled);
  ImGui::SameLine();
  ImGui::Checkbox("pin", &v.pinned);
  widgetRects().noteLastItem("ab.pin");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("keep this panel open after Revert or Accept");
  if (!v.note.empty()) ImGui::TextWrapped("%s", v.note.c_str());
  const live::ABState::View* shown = v.viewFor(mode);
  if (!v.results.empty() && !shown) {
    std::string compared;
    for (const auto& r : v.results) compared += (compared.empty() ? "" : ", ") + r.pipeline;
    ImGui::TextWrapped("the last edit rebuilt no pipeline of the %s mode (compared: %s)", mode.c_str(),
                       compared.c_str());
  }
  if (shown) {
    const auto& r = shown->result;
    const char* image = eval::imageVerdictName(r.image.verdict);
    const ImVec4 imageColour = r.image.verdict == eval::ImageVerdict::Changed ? ImVec4(1.0f, 0.75f, 0.3f, 1)
                                                                              : ImVec4(0.5f, 1.0f, 0.5f, 1);
    ImGui::Text("%s (%s)", r.pipeline.c_str(), r.mode.c_str());
    ImGui::TextColored(imageColour, "image: %s%s", image,
                       r.image.verdict == eval::ImageVerdict::Changed
                           ? (r.image.meanShiftSignificant ? " (mean shifted)" : " (mean within noise)")
                           : "");
    ImGui::Text("rmse %.3g  relMSE %.3g  max %.3g", r.image.rmse, r.image.relMse, r.image.maxAbsDiff);
    ImGui::Text("pixels changed %.1f%%", 100.0 * r.image.changedPixelFraction);
    const char* speed = eval::speedVerdictName(r.speed.verdict);
    const ImVec4 speedColour = r.speed.verdict == eval::SpeedVerdict::Slower   ? ImVec4(1.0f, 0.4f, 0.4f, 1)
                               : r.speed.verdict == eval::SpeedVerdict::Faster ? ImVec4(0.5f, 1.0f, 0.5f, 1)
                                                                               : ImVec4(0.8f, 0.8f, 0.8f, 1);
    ImGui::TextColored(speedColour, "speed: %s  x%.2f [%.2f, %.2f]", speed, r.speed.ratio, r.speed.spread[0],
                       r.speed.spread[1]);
    ImGui::Text("ms/sample old %.2f new %.2f", r.speed.oldMsPerSample, r.speed.newMsPerSample);
    if (v.results.size() > 1) ImGui::Text("+%zu more pipelines (stats JSON)", v.results.size() - 1);
    ImGui::Text("A/B %.0f ms, edit %.0f ms", v.abMs, v.editMs);
    ImGui::TextWrapped("budget %s", v.plan.summary().c_str());

    int show = int(v.show);
    ImGui::RadioButton("old", &show, int(live::ABState::Show::Old));
    ImGui::SameLine();
    ImGui::RadioButton("new", &show, int(live::ABState::Show::New));
    ImGui::SameLine();
    ImGui::RadioButton("split", &show, int(live::ABState::Show::Split));
    ImGui::SameLine();
    ImGui::RadioButton("diff", &show, int(live::ABState::Show::Difference));
    v.show = live::ABState::Show(show);
    if (shown->width > 0) {
      const float size = std::max(ImGui::GetContentRegionAvail().x, 32.0f);
      const ImVec2 at = ImGui::GetCursorScreenPos();
      ImDrawList* dl = ImGui::GetWindowDrawList();
      const uint32_t w = shown->width, h = shown->height;
      switch (v.show) {
        case live::ABState::Show::Old:
          drawPixels(dl, at, size, w, h, shown->oldRgba, shown->oldRgba, w);
          break;
        case live::ABState::Show::New:
          drawPixels(dl, at, size, w, h, shown->newRgba, shown->newRgba, w);
          break;
        case live::ABState::Show::Split:
          drawPixels(dl, at, size, w, h, shown->oldRgba, shown->newRgba, w / 2);
          dl->AddLine(ImVec2(at.x + size * 0.5f, at.y), ImVec2(at.x + size * 0.5f, at.y + size),
                      IM_COL32(255, 255, 255, 200));
          break;
        case live::ABState::Show::Difference:
          drawPixels(dl, at, size, w, h, shown->diffRgba, shown->diffRgba, w);
          break;
      }
      ImGui::Dummy(ImVec2(size, size * float(h) / float(std::max(w, h))));
      if (v.show == live::ABState::Show::Split) ImGui::Text("left: old   right: new");
      if (v.show == live::ABState::Show::Difference)
        ImGui::Text("|new - old|: black 0 .. white %.3g", shown->diffScale);
    }
  }
  if (!v.results.empty() && !v.decided) {
    if (ImGui::Button("Revert")) v.revertRequested = true;
    widgetRects().noteLastItem("ab.revert");
    ImGui::SameLine();
    if (ImGui::Button("Accept")) v.acceptRequested = true;
    widgetRects().noteLastItem("ab.accept");
  }
  ImGui::End();
}

}  // namespace wb::app
