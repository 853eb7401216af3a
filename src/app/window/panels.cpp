#include "app/window/panels.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <ctime>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/window/heat_legend.h"
#include "app/window/instruments_panel.h"
#include "app/window/number_text.h"
#include "app/window/parameter_panel.h"
#include "app/window/widget_rects.h"
#include "common/paths.h"

namespace wb::app {
namespace {

std::string relativeToRoot(const std::filesystem::path& p) {
  std::error_code ec;
  auto rel = std::filesystem::relative(p, shaderDir(), ec);
  return ec || rel.empty() ? p.string() : rel.string();
}

// The parameters of the active mode (render/parameters.h), then the window's own controls.
void renderPanel(PanelContext& c) {
  auto& st = c.session.state();
  // The mode whose renderer draws the image: while another one is being made, its controls wait for it.
  const render::RenderMode mode = c.session.mode();
  drawParameterGroup("Render", st.params, mode);
  if (mode != render::RenderMode::PathTrace) {
    ImGui::Separator();
    drawParameterGroup("Hybrid", st.params, mode);
  }
  if (const std::string inUse = c.session.modeInUse(); !inUse.empty())
    ImGui::TextDisabled("%s", inUse.c_str());
  if (const uint32_t kept = c.session.pathTracerSamplesKept(); kept > 0)
    ImGui::TextDisabled("pathtrace: %u samples kept, resumed on going back", kept);
  ImGui::Separator();
  if (ImGui::Button(st.paused ? "Resume" : "Pause")) st.paused = !st.paused;
  ImGui::SameLine();
  if (ImGui::Button("Reset accumulation")) st.resetAccumulation = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset camera")) st.resetCamera = true;
  if (st.fixedSize) {
    ImGui::Text("trace size %ux%u (--size)", c.session.imageWidth(), c.session.imageHeight());
  }
  ImGui::SliderFloat("resolution scale", &st.resolutionScale, 0.1f, 1.0f, "%.2f");
  if (c.session.previews()) {
    ImGui::Checkbox("preview after changes", &st.preview);
    widgetRects().noteLastItem("preview");
  }
  ImGui::SliderFloat("trace budget ms", &st.budgetMs, 5.0f, 200.0f, "%.0f");
  ImGui::Checkbox("vsync", &st.vsync);
  ImGui::SameLine();
  ImGui::TextDisabled("%s", c.presentMode.c_str());
  ImGui::Separator();
  for (const char* name : {"exposure", "tonemap"})
    drawParameter(*render::findParameter(name).info, st.params);
  int cameraMode = c.camera.mode() == CameraMode::Fly ? 1 : 0;
  if (ImGui::Combo("camera", &cameraMode,
                   "orbit (drag, wheel, shift/middle pan)\0fly (right-drag look, WASD QE)\0")) {
    c.camera.setMode(cameraMode ? CameraMode::Fly : CameraMode::Orbit);
  }
  if (c.camera.mode() == CameraMode::Fly) ImGui::SliderFloat("fly speed", &c.camera.speed, 0.05f, 5.0f);
  if (ImGui::Button("Save image (F12)")) st.saveRequest = "";
  if (!c.lastSaved.empty()) {
    ImGui::SameLine();
    ImGui::TextDisabled("%s", c.lastSaved.c_str());
  }
}

void inspectPanel(PanelContext& c) {
  auto& st = c.session.state();
  const bool debugViews = c.session.displayFrame().debugViews;
  if (debugViews) {
    drawParameter(*render::findParameter("view").info, st.params);
  } else {
    ImGui::TextDisabled("debug views are the path tracer's");
  }
  drawCostSummary(c.session);
  drawAssertsSection(c.session);
  drawInspectorSection(st, c.session.inspection(), debugViews);
  drawPrintsSection(c.session);
  ImGui::Separator();
  ImGui::TextDisabled("click the image to select an object (hover names it)");
  if (!c.selected) {
    ImGui::TextUnformatted("nothing selected");
    return;
  }
  const PickResult& p = *c.selected;
  ImGui::Text("selected: instance %d (%s)", p.instance, p.nodeName.c_str());
  ImGui::Text("mesh %d (%s) primitive %d triangle %d", p.mesh, p.meshName.c_str(), p.primitive, p.triangle);
  ImGui::Text("position %.3f %.3f %.3f", p.position.x, p.position.y, p.position.z);
  ImGui::Text("distance %.4f", p.distance);
  ImGui::Text("shading n %.3f %.3f %.3f", p.shadingNormal.x, p.shadingNormal.y, p.shadingNormal.z);
  ImGui::Text("geometric n %.3f %.3f %.3f", p.geometricNormal.x, p.geometricNormal.y, p.geometricNormal.z);
  ImGui::Text("uv %.4f %.4f", p.uv.x, p.uv.y);
  if (p.material < 0 || size_t(p.material) >= st.materials.size()) return;
  ImGui::Separator();
  ImGui::Text("material %d: %s", p.material, p.materialName.c_str());
  gpu::Material& m = st.materials[size_t(p.material)];
  bool changed = false;
  changed |= ImGui::ColorEdit4("base colour", &m.baseColorFactor.x, ImGuiColorEditFlags_Float);
  changed |= ImGui::SliderFloat("metallic", &m.metallic, 0.0f, 1.0f);
  changed |= ImGui::SliderFloat("roughness", &m.roughness, 0.0f, 1.0f);
  changed |=
      ImGui::ColorEdit3("emissive", &m.emissive.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
  changed |= ImGui::SliderFloat("specular", &m.specularFactor, 0.0f, 1.0f);
  changed |= ImGui::ColorEdit3("specular colour", &m.specularColorFactor.x, ImGuiColorEditFlags_Float);
  ImGui::TextDisabled("alpha mode %u cutoff %.2f  textures: base %d normal %d mr %d emissive %d", m.alphaMode,
                      m.alphaCutoff, m.baseColorTexture, m.normalTexture, m.metallicRoughnessTexture,
                      m.emissiveTexture);
  if (changed) st.materialsDirty = true;
  if (ImGui::Button("Revert material") && size_t(p.material) < c.session.render().scene().materials.size()) {
    m = c.session.render().scene().materials[size_t(p.material)];
    st.materialsDirty = true;
  }
}

void lightsPanel(PanelContext& c) {
  auto& st = c.session.state();
  if (st.lights.empty()) ImGui::TextDisabled("the scene has no directional light");
  for (size_t i = 0; i < st.lights.size(); ++i) {
    ImGui::PushID(int(i));
    auto& l = st.lights[i];
    ImGui::Text("directional light %zu", i);
    // Direction as azimuth / elevation of where the light comes from.
    const glm::vec3 from = -glm::normalize(l.direction);
    float elevation = glm::degrees(std::asin(std::clamp(from.y, -1.0f, 1.0f)));
    float azimuth = glm::degrees(std::atan2(from.x, from.z));
    bool changed = ImGui::SliderFloat("azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
    changed |= ImGui::SliderFloat("elevation", &elevation, -89.0f, 89.0f, "%.1f deg");
    const float peak = std::max({l.radiance.x, l.radiance.y, l.radiance.z, 1e-6f});
    glm::vec3 colour = l.radiance / peak;
    float intensity = peak;
    changed |= ImGui::ColorEdit3("colour", &colour.x);
    changed |= ImGui::DragFloat("intensity", &intensity, 0.05f, 0.0f, 1000.0f);
    if (changed) {
      const float az = glm::radians(azimuth), el = glm::radians(elevation);
      const glm::vec3 dirFrom(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
      l.direction = -dirFrom;
      l.radiance = colour * intensity;
      st.lightsDirty = true;
    }
    if (ImGui::Button("Revert light") && i < c.session.render().scene().lights.size()) {
      l = c.session.render().scene().lights[i];
      st.lightsDirty = true;
    }
    ImGui::PopID();
  }
  ImGui::Separator();
  ImGui::TextUnformatted("environment");
  drawParameterGroup("Environment", st.params, c.session.mode());
  if (!st.envError.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", st.envError.c_str());
}

void shadersPanel(PanelContext& c) {
  bool autoReload = c.session.loop().hot().autoReload();
  if (ImGui::Checkbox("auto reload on save", &autoReload)) c.session.loop().hot().setAutoReload(autoReload);
  ImGui::SameLine();
  if (ImGui::Button("Reload all (F5)")) c.session.state().reloadShaders = true;
  auto& ab = c.session.ab();
  if (!ab.open && (!ab.results.empty() || !ab.note.empty()) && ImGui::Button("Show the last A/B comparison"))
    ab.open = true;
  const std::string err = c.session.loop().hot().currentError();
  if (!err.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", err.c_str());
    ImGui::PopStyleColor();
  }
  const auto files = c.session.render().library().fileStatuses();
  if (ImGui::BeginTable("files", 4, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("file", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn("status");
    ImGui::TableSetupColumn("ms");
    ImGui::TableSetupColumn("cache");
    ImGui::TableHeadersRow();
    for (const auto& [path, f] : files) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(relativeToRoot(path).c_str());
      if (ImGui::IsItemHovered() && !f.programs.empty()) {
        std::string tip = "used by:";
        for (const auto& p : f.programs) tip.append("\n  ").append(p);
        for (const auto& d : f.diagnostics) tip.append("\n").append(d.toString());
        ImGui::SetTooltip("%s", tip.c_str());
      }
      ImGui::TableNextColumn();
      if (f.ok) {
        ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1), "ok");
      } else {
        ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1), "error");
      }
      ImGui::TableNextColumn();
      ImGui::Text("%.1f", f.lastCompileMs);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(f.lastCacheHit ? "hit" : "miss");
    }
    ImGui::EndTable();
  }
  if (ImGui::TreeNode("pipelines per file")) {
    for (const auto& [path, f] : files) {
      std::string progs;
      for (const auto& p : f.programs) {
        if (!progs.empty()) progs.append(", ");
        progs.append(p);
      }
      ImGui::BulletText("%s: %s", relativeToRoot(path).c_str(), progs.c_str());
    }
    ImGui::TreePop();
  }
  const auto history = c.session.loop().hot().history();
  if (ImGui::TreeNodeEx("reload history", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (auto it = history.rbegin(); it != history.rend() && it - history.rbegin() < 12; ++it) {
      const auto& e = *it;
      const std::time_t t = std::chrono::system_clock::to_time_t(e.when);
      char when[16];
      std::strftime(when, sizeof when, "%H:%M:%S", std::localtime(&t));
      std::string files;
      for (const auto& f : e.filesChanged) {
        if (!files.empty()) files.append(", ");
        files.append(relativeToRoot(f));
      }
      if (files.empty()) files = "(reload all)";
      ImGui::TextColored(e.ok ? ImVec4(0.6f, 0.9f, 0.6f, 1) : ImVec4(1, 0.45f, 0.4f, 1), "%s %s %s", when,
                         e.ok ? "ok" : "FAILED", files.c_str());
      ImGui::TextDisabled("   compile %.1f ms, pipeline %.1f ms, edit->pipeline %.0f ms, edit->frame %.0f ms",
                          e.compileMs, e.pipelineMs, e.editToNewPipelineMs, e.editToFirstFrameMs);
    }
    ImGui::TreePop();
  }
}

void errorSection(PanelContext& c) {
  const auto& le = c.session.liveError();
  static std::string refEdit;
  static bool refInit = false;
  if (!refInit) {
    refEdit = c.session.state().referencePath;
    refInit = true;
  }
  ImGui::InputText("##reference", &refEdit);
  ImGui::SameLine();
  if (ImGui::Button("Load ref")) c.session.state().referencePath = refEdit;
  ImGui::SameLine();
  if (ImGui::Button("Clear")) c.session.state().referencePath = refEdit = "";
  if (!le.error().empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", le.error().c_str());
  const auto last = le.latest();
  if (!last) {
    ImGui::TextDisabled(le.hasReference() ? "error vs reference: waiting for a sample"
                                          : "noise estimate: needs 2 samples (n vs n/2)");
    // The plot's room stays: a restart does not move the sections below under the cursor.
    ImGui::Dummy(ImVec2(ImGui::GetContentRegionAvail().x, 50));
    return;
  }
  ImGui::Text("%s at %u spp: RMSE %.4g  relMSE %.4g", last->estimated ? "noise est." : "error vs ref",
              last->samples, last->rmse, last->relMse);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(last->estimated
                          ? "No reference loaded: mean((I_n - I_n/2)^2) estimates the noise part of the MSE "
                            "(blind to bias; Sobol samples make it an indicator)."
                          : "Against %s (box-downsampled when it is an integer multiple of the trace size).",
                      le.referenceName().c_str());
  }
  std::vector<float> logRel;
  for (const auto& p : le.history()) logRel.push_back(float(std::log10(std::max(p.relMse, 1e-12))));
  if (logRel.size() >= 2) {
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "log10 relMSE, %zu checkpoints", logRel.size());
    ImGui::PlotLines("##error", logRel.data(), int(logRel.size()), 0, overlay, FLT_MAX, FLT_MAX,
                     ImVec2(ImGui::GetContentRegionAvail().x, 50));
  } else {
    ImGui::Dummy(ImVec2(ImGui::GetContentRegionAvail().x, 50));
  }
}

void statsPanel(PanelContext& c) {
  const auto& pt = c.session.progressive();
  std::string target;
  if (c.session.state().params.render.spp)
    target.append(" / ").append(std::to_string(c.session.state().params.render.spp));
  ImGui::Text("%s %u%s%s", c.session.sampleUnit(), c.session.samples(), target.c_str(),
              c.session.inPreview() ? "  (preview)" : "");
  ImGui::Text("trace %ux%u  elapsed %.1f s", c.session.imageWidth(), c.session.imageHeight(),
              c.session.secondsSinceReset());
  if (c.session.counters().pathCount == 0) {  // a renderer that does not count paths and rays
    ImGui::Text("%s/s %.1f", c.session.sampleUnit(),
                c.session.samples() / std::max(c.session.secondsSinceReset(), 1e-6));
  } else {
    const double secs = std::max(c.session.gpuTraceSeconds(), 1e-6);
    ImGui::Text("paths/s %s  rays/s %s", humanCount(c.session.counters().pathCount / secs).c_str(),
                humanCount(c.session.counters().rayCount / secs).c_str());
    ImGui::Text("tracer rate %.0f px/ms  NaN/Inf dropped %u", pt.pixelsPerMs(),
                c.session.counters().droppedSamples);
  }
  const auto values = c.frames.values();
  char overlay[96];
  std::snprintf(overlay, sizeof overlay, "frame %.1f ms (mean %.1f, max %.1f)", c.frames.last(),
                c.frames.mean(), c.frames.max());
  ImGui::PlotLines("##frametimes", values.data(), int(values.size()), 0, overlay, 0.0f,
                   std::max(50.0f, c.frames.max() * 1.1f), ImVec2(ImGui::GetContentRegionAvail().x, 60));
  drawPassTimes(c.session, c.displayGpuMs);
  errorSection(c);
  ImGui::TextDisabled("%s", c.session.render().context().deviceName().c_str());
}

}  // namespace

float sidePanelWidth(float windowWidth) {
  return std::min(400.0f, std::floor(windowWidth * 0.45f));
}

float drawSidePanel(PanelContext& c, float windowWidth, float windowHeight, float& width) {
  if (!c.session.state().showPanel) return 0.0f;
  // Resizable by its right edge, between a narrow panel and most of the window.
  const float minWidth = std::min(200.0f, windowWidth), maxWidth = std::max(minWidth, windowWidth * 0.75f);
  if (width <= 0.0f) width = sidePanelWidth(windowWidth);
  width = std::clamp(width, minWidth, maxWidth);
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(width, windowHeight));
  ImGui::SetNextWindowSizeConstraints(ImVec2(minWidth, windowHeight), ImVec2(maxWidth, windowHeight));
  ImGui::Begin("workbench", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoTitleBar);
  // A drag of the edge shows in the window's size this frame: the next frame starts from it.
  width = ImGui::GetWindowWidth();
  widgetRects().note("side_panel", Rect{0.0f, 0.0f, width, windowHeight});
  ImGui::PushItemWidth(std::floor(ImGui::GetContentRegionAvail().x * 0.55f));
  if (ImGui::CollapsingHeader("Render", ImGuiTreeNodeFlags_DefaultOpen)) renderPanel(c);
  if (ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) statsPanel(c);
  // A pixel was just picked: open the Inspect section and scroll the panel to it.
  const bool showInspect = c.session.state().inspectOpenPanel > 0;
  if (showInspect) {
    --c.session.state().inspectOpenPanel;
    ImGui::SetNextItemOpen(true);
  }
  if (ImGui::CollapsingHeader("Inspect")) {
    if (showInspect) ImGui::SetScrollHereY(0.0f);
    inspectPanel(c);
  }
  if (ImGui::CollapsingHeader("Lights and environment")) lightsPanel(c);
  if (ImGui::CollapsingHeader(
          "Shaders", c.session.loop().hot().currentError().empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    shadersPanel(c);
  if (ImGui::CollapsingHeader("Keys")) {
    ImGui::TextWrapped(
        "left-drag: orbit (a drag across the image turns 180 degrees); shift-, middle- or right-drag: pan; "
        "wheel: dolly; Home: reset the camera; click on the image: select the object and inspect the pixel; "
        "Tab: hide the panels (the image takes the window); F5: reload every shader; F12: save the image; "
        "Esc or Ctrl+Q: quit");
  }
  ImGui::PopItemWidth();
  ImGui::End();
  return width;
}

void drawOverlays(PanelContext& c, const Rect& view) {
  {
    const float radius =
        0.5f * glm::length(c.session.render().scene().bounds.max - c.session.render().scene().bounds.min);
    drawInspectorOverlay(c.session.state(), c.session.inspection(), c.camera.state(), c.session.imageWidth(),
                         c.session.imageHeight(), view, std::max(radius, 1e-3f));
    drawAssertMarks(c.session, view);
  }
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  // Hovering names the object under the cursor (a click selects it for the material editor).
  if (c.hover && !ImGui::GetIO().WantCaptureMouse) {
    const std::string label =
        c.hover->nodeName + (c.hover->materialName.empty() ? "" : " / ") + c.hover->materialName;
    const ImVec2 m = ImGui::GetIO().MousePos;
    const ImVec2 ls = ImGui::CalcTextSize(label.c_str());
    const ImVec2 at(std::min(m.x + 14, view.x + view.w - ls.x - 6), m.y + 14);
    dl->AddRectFilled(ImVec2(at.x - 3, at.y - 2), ImVec2(at.x + ls.x + 3, at.y + ls.y + 2),
                      IM_COL32(0, 0, 0, 170), 3.0f);
    dl->AddText(at, IM_COL32(255, 255, 255, 255), label.c_str());
  }
  // A heat-map view's colour bar: what the colours mean, in which unit and scale.
  if (const live::DisplayFrame d = c.session.displayFrame(); d.debugViews) {
    const auto& cost = c.session.instruments().cost();
    if (const auto legend =
            heatLegend(c.session.state().params.display.view, d.maxVertices, cost ? &*cost : nullptr))
      widgetRects().note("legend", drawHeatLegend(*legend, view));
  }
  char status[192];
  const bool done = !c.session.tracing() && !c.session.state().paused;
  std::snprintf(status, sizeof status, "%s  %u %s%s  %ux%u  %.1f s  shown every %.0f ms%s",
                render::renderModeName(c.session.mode()), c.session.samples(), c.session.sampleUnit(),
                c.session.inPreview() ? " (preview)" : "", c.session.imageWidth(), c.session.imageHeight(),
                c.session.secondsSinceReset(), c.frames.last(),
                c.session.state().paused ? "  PAUSED" : (done ? "  done" : ""));
  const ImVec2 pos(view.x + 6, view.y + view.h - ImGui::GetTextLineHeight() - 6);
  const ImVec2 size = ImGui::CalcTextSize(status);
  dl->AddRectFilled(ImVec2(pos.x - 3, pos.y - 2), ImVec2(pos.x + size.x + 3, pos.y + size.y + 2),
                    IM_COL32(0, 0, 0, 160), 3.0f);
  dl->AddText(pos, IM_COL32(230, 230, 230, 255), status);

  // Top right: a rebuild or a mode switch in progress (stage, elapsed), else what the last edit cost.
  char busy[192] = "";
  bool active = true;
  const auto hs = c.session.loop().hot().status();
  if (hs.stage != live::HotReload::Status::Stage::Idle) {
    std::snprintf(busy, sizeof busy, "%s  %.1f s", live::HotReload::stageName(hs.stage), hs.elapsedMs * 1e-3);
  } else if (!c.session.modeSwitch().empty()) {
    std::snprintf(busy, sizeof busy, "preparing %s  %.1f s", c.session.modeSwitch().c_str(),
                  c.session.modeSwitchSeconds());
  } else if (const auto last = c.session.loop().hot().lastEvent(); last && last->ok) {
    active = false;
    const auto& e = *last;
    if (e.pipelinesRebuilt.empty()) {
      std::snprintf(busy, sizeof busy, "last edit: unchanged SPIR-V, nothing rebuilt");
    } else if (e.editToFirstFrameMs >= 0) {
      std::snprintf(busy, sizeof busy,
                    "last edit: compile %.0f ms + pipeline %.0f ms, on screen after %.2f s", e.compileMs,
                    e.pipelineMs, e.editToFirstFrameMs * 1e-3);
    }
  }
  float bannerTop = view.y + 6;  // the error banner goes under the busy line, which stays readable
  if (busy[0]) {
    const ImVec2 bs = ImGui::CalcTextSize(busy);
    bannerTop += bs.y + 10;
    const ImVec2 bp(view.x + view.w - bs.x - 10, view.y + 6);
    dl->AddRectFilled(ImVec2(bp.x - 4, bp.y - 2), ImVec2(bp.x + bs.x + 4, bp.y + bs.y + 2),
                      active ? IM_COL32(170, 110, 0, 220) : IM_COL32(0, 0, 0, 140), 3.0f);
    dl->AddText(bp, IM_COL32(255, 255, 255, 255), busy);
  }

  const std::string err = c.session.loop().hot().currentError();
  if (err.empty()) return;
  std::string text = "shader error (still rendering with the last good pipeline):\n";
  // Paths relative to the shader folder keep the banner readable.
  const std::string prefix = shaderDir().string() + "/";
  size_t at = 0;
  for (size_t hit; (hit = err.find(prefix, at)) != std::string::npos; at = hit + prefix.size()) {
    text.append(err, at, hit - at);
  }
  text.append(err, at, std::string::npos);
  if (text.size() > 900) text.resize(900), text.append("...");
  const float wrap = std::max(view.w - 24.0f, 50.0f);
  const ImVec2 ts = ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap);
  const ImVec2 a(view.x + 6, bannerTop), b(view.x + 18 + ts.x, bannerTop + 12 + ts.y);
  dl->AddRectFilled(a, b, IM_COL32(150, 20, 20, 225), 4.0f);
  dl->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(a.x + 6, a.y + 6), IM_COL32(255, 240, 240, 255),
              text.c_str(), nullptr, wrap);
}

}  // namespace wb::app
