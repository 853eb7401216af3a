#include "app/window/ab_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "eval/metrics.h"

namespace wb::app {

void ABView::set(const std::vector<live::ABOutcome>& outcomes,
                 const std::vector<live::HotReload::InstalledPass>& programs, double ms,
                 double editToFirstFrameMs) {
  results.clear();
  for (const auto& o : outcomes) results.push_back(o.result);
  installed = programs;
  abMs = ms;
  editMs = editToFirstFrameMs;
  decided = false;
  note.clear();
  width = height = 0;
  oldRgba.clear();
  newRgba.clear();
  diffRgba.clear();
  if (!outcomes.empty()) {
    const auto& o = outcomes.front();
    width = o.oldImage.width;
    height = o.oldImage.height;
    oldRgba = eval::tonemapToSrgb8(o.oldImage);
    newRgba = eval::tonemapToSrgb8(o.newImage);
    // Full scale at the largest difference, so that a change on a few pixels stays visible (a NaN/Inf
    // difference: the 99th percentile instead).
    const double largest = results.front().image.maxAbsDiff;
    diffRgba = eval::errorHeatmap(o.oldImage, o.newImage, std::isfinite(largest) ? largest : 0.0, &diffScale);
  }
  if (!userChose && editMs > 0 && abMs > kMaxCostRatio * editMs) {
    enabled = false;
    char buf[160];
    std::snprintf(buf, sizeof buf, "off: the comparison took %.0f ms, over %.0f%% of the edit's %.0f ms",
                  abMs, kMaxCostRatio * 100.0, editMs);
    note = buf;
  }
}

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

void drawABPanel(ABView& v, float viewRight, float viewBottom) {
  if (v.results.empty() && v.note.empty()) return;
  const float panelW = 300;
  ImGui::SetNextWindowPos(ImVec2(viewRight - panelW - 10, viewBottom - 10), ImGuiCond_Always, ImVec2(0, 1));
  ImGui::SetNextWindowSize(ImVec2(panelW, 0), ImGuiCond_Always);
  ImGui::Begin("A/B: old vs new", nullptr,
               ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  if (ImGui::Checkbox("compare after each edit", &v.enabled)) v.userChose = true;
  if (!v.note.empty()) ImGui::TextWrapped("%s", v.note.c_str());
  if (!v.results.empty()) {
    const auto& r = v.results.front();
    const char* image = eval::imageVerdictName(r.image.verdict);
    const ImVec4 imageColour = r.image.verdict == eval::ImageVerdict::Changed ? ImVec4(1.0f, 0.75f, 0.3f, 1)
                                                                              : ImVec4(0.5f, 1.0f, 0.5f, 1);
    ImGui::Text("%s", r.pipeline.c_str());
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

    int show = int(v.show);
    ImGui::RadioButton("old", &show, int(ABView::Show::Old));
    ImGui::SameLine();
    ImGui::RadioButton("new", &show, int(ABView::Show::New));
    ImGui::SameLine();
    ImGui::RadioButton("split", &show, int(ABView::Show::Split));
    ImGui::SameLine();
    ImGui::RadioButton("diff", &show, int(ABView::Show::Difference));
    v.show = ABView::Show(show);
    if (v.width > 0) {
      const float size = panelW - 20;
      const ImVec2 at = ImGui::GetCursorScreenPos();
      ImDrawList* dl = ImGui::GetWindowDrawList();
      switch (v.show) {
        case ABView::Show::Old:
          drawPixels(dl, at, size, v.width, v.height, v.oldRgba, v.oldRgba, v.width);
          break;
        case ABView::Show::New:
          drawPixels(dl, at, size, v.width, v.height, v.newRgba, v.newRgba, v.width);
          break;
        case ABView::Show::Split:
          drawPixels(dl, at, size, v.width, v.height, v.oldRgba, v.newRgba, v.width / 2);
          dl->AddLine(ImVec2(at.x + size * 0.5f, at.y), ImVec2(at.x + size * 0.5f, at.y + size),
                      IM_COL32(255, 255, 255, 200));
          break;
        case ABView::Show::Difference:
          drawPixels(dl, at, size, v.width, v.height, v.diffRgba, v.diffRgba, v.width);
          break;
      }
      ImGui::Dummy(ImVec2(size, size * float(v.height) / float(std::max(v.width, v.height))));
      if (v.show == ABView::Show::Split) ImGui::Text("left: old   right: new");
      if (v.show == ABView::Show::Difference) ImGui::Text("|new - old|: black 0 .. white %.3g", v.diffScale);
    }
    if (!v.decided) {
      if (ImGui::Button("Revert")) v.revertRequested = true;
      ImGui::SameLine();
      if (ImGui::Button("Accept")) v.acceptRequested = true;
    }
  }
  ImGui::End();
}

}  // namespace wb::app
