#include "app/window/path_inspector_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>

#include "app/window/widget_rects.h"
#include "render/path_tracer.h"
#include "shared/brdf.h"

namespace wb::app {
namespace {

float luminance(const glm::vec3& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// Throughput (luminance) as a colour: blue at 0, green at 1, red from 2 on (Russian roulette's boost).
ImU32 throughputColor(float t) {
  const float x = std::isfinite(t) ? std::clamp(t / 2.0f, 0.0f, 1.0f) : 1.0f;
  const glm::vec3 stops[] = {{0.2f, 0.35f, 1.0f}, {0.1f, 0.9f, 0.3f}, {1.0f, 0.2f, 0.1f}};
  const glm::vec3 c =
      x < 0.5f ? glm::mix(stops[0], stops[1], x * 2.0f) : glm::mix(stops[1], stops[2], x * 2.0f - 1.0f);
  return IM_COL32(int(c.x * 255), int(c.y * 255), int(c.z * 255), 235);
}

struct Projector {
  glm::mat4 view, proj;
  float znear;
  glm::vec2 size;
  Rect image;

  // The segment a-b clipped to the front of the near plane, in screen coordinates; false when all behind.
  bool segment(glm::vec3 a, glm::vec3 b, ImVec2& sa, ImVec2& sb) const {
    glm::vec4 va = view * glm::vec4(a, 1.0f), vb = view * glm::vec4(b, 1.0f);
    const float limit = -znear * 1.01f;  // view space looks down -z
    if (va.z > limit && vb.z > limit) return false;
    if (va.z > limit) va = glm::mix(vb, va, (vb.z - limit) / (vb.z - va.z));
    if (vb.z > limit) vb = glm::mix(va, vb, (va.z - limit) / (va.z - vb.z));
    sa = screen(va);
    sb = screen(vb);
    return true;
  }
  ImVec2 screen(const glm::vec4& viewPoint) const {
    const glm::vec4 clip = proj * viewPoint;
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const glm::vec2 pixel = (ndc + 1.0f) * 0.5f * size;
    return ImVec2(image.x + pixel.x / size.x * image.w, image.y + pixel.y / size.y * image.h);
  }
};

void dashed(ImDrawList* dl, ImVec2 a, ImVec2 b, ImU32 color) {
  const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
  const float dash = 6.0f;
  for (float t = 0.0f; t < len; t += 2.0f * dash) {
    const float t1 = std::min(t + dash, len);
    dl->AddLine(ImVec2(a.x + dx * t / len, a.y + dy * t / len),
                ImVec2(a.x + dx * t1 / len, a.y + dy * t1 / len), color, 1.5f);
  }
}

void drawPath(ImDrawList* dl, const Projector& pr, const render::InspectedSample& s, float radius,
              bool faint) {
  const int alpha = faint ? 90 : 255;
  auto withAlpha = [&](ImU32 c) { return (c & 0x00ffffffu) | (ImU32(alpha) << 24); };
  glm::vec3 from = s.record.cameraOrigin;
  glm::vec3 throughput(1.0f);
  for (size_t k = 0; k < s.vertices.size(); ++k) {
    const auto& v = s.vertices[k].record;
    ImVec2 a, b;
    if (pr.segment(from, v.position, a, b))
      dl->AddLine(a, b, withAlpha(throughputColor(luminance(throughput))), 2.0f);
    // Shadow rays: dashed towards the light, green when they reached it, red when blocked.
    for (const auto& l : s.vertices[k].lights) {
      if (l.status != WB_INSPECT_NEE_TRACED) continue;
      const float len = l.distance < 1e29f ? l.distance : radius * 0.35f;
      if (pr.segment(v.position, v.position + l.direction * len, a, b))
        dashed(dl, a, b, withAlpha(l.visible ? IM_COL32(80, 230, 90, 255) : IM_COL32(230, 60, 60, 255)));
    }
    const bool bad = s.firstNonFinite && s.firstNonFinite->vertex == int(k);
    if (pr.segment(v.position, v.position, a, b))
      dl->AddCircleFilled(a, bad ? 5.0f : 3.0f,
                          withAlpha(bad ? IM_COL32(255, 0, 255, 255) : IM_COL32(255, 255, 255, 255)));
    from = v.position;
    throughput = v.throughput;
  }
  if (s.record.escaped) {
    ImVec2 a, b;
    const glm::vec3 end = from + s.record.escapeDirection * radius * 0.5f;
    if (pr.segment(from, end, a, b)) {
      dl->AddLine(a, b, withAlpha(throughputColor(luminance(s.record.escapeThroughput))), 2.0f);
      dl->AddCircle(b, 4.0f, withAlpha(IM_COL32(255, 255, 255, 255)));
    }
  }
}

std::string vec3Text(const glm::vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.4g %.4g %.4g", v.x, v.y, v.z);
  return buf;
}

void vertexTooltip(const render::InspectedVertex& iv) {
  const auto& v = iv.record;
  ImGui::BeginTooltip();
  ImGui::Text("position %s  distance %.4g", vec3Text(v.position).c_str(), v.distance);
  ImGui::Text("geometric n %s  shading n %s", vec3Text(v.geometricNormal).c_str(),
              vec3Text(v.shadingNormal).c_str());
  ImGui::Text("%s face%s  instance %d geometry %d primitive %d material %d",
              (v.flags & WB_INSPECT_FRONT_FACE) ? "front" : "back",
              (v.flags & WB_INSPECT_NORMAL_FLIPPED) ? " (normal flipped)" : "", v.instance, v.geometry,
              v.primitive, v.material);
  ImGui::Text("emitted %s  MIS %.4g", vec3Text(v.emitted).c_str(), v.emissionMis);
  ImGui::Text("%s lobe (p %.3g)  direction %s", render::inspectLobeName(v.lobe), v.lobeProbability,
              vec3Text(v.direction).c_str());
  ImGui::Text("f %s  cos %.4g  pdf %.4g  weight %s", vec3Text(v.brdf).c_str(), v.cosine, v.pdf,
              vec3Text(v.weight).c_str());
  ImGui::Text("throughput in %s  out %s", vec3Text(v.throughputIn).c_str(), vec3Text(v.throughput).c_str());
  ImGui::Text("Russian roulette: %s (survival %.3g)", render::inspectRrName(v.rrOutcome), v.rrProbability);
  for (const auto& l : iv.lights) {
    ImGui::Separator();
    ImGui::Text("%s %d: %s%s", render::inspectLightKindName(l.kind), l.index,
                render::inspectLightStatusName(l.status),
                l.status == WB_INSPECT_NEE_TRACED ? (l.visible ? ", visible" : ", blocked") : "");
    ImGui::Text("  light pdf %.4g%s  BRDF pdf %.4g  MIS %.4g", l.lightPdf,
                l.kind == WB_INSPECT_LIGHT_DIRECTIONAL && l.lightPdf == 0.0f ? " (delta)" : "", l.brdfPdf,
                l.misWeight);
    ImGui::Text("  Le %s  contribution %s", vec3Text(l.radiance).c_str(), vec3Text(l.contribution).c_str());
  }
  ImGui::Text("added to the sample %s", vec3Text(iv.added).c_str());
  ImGui::Text("clocks: trace %u  shading %u  shadow rays %u", v.traceClocks, v.shadeClocks, v.shadowClocks);
  ImGui::EndTooltip();
}

void hybridSection(const live::PixelInspection& view) {
  if (!view.hybrid() || view.hybrid()->frameIndex == WB_HYBRID_NO_INSPECT) {
    ImGui::TextDisabled("waiting for a frame");
    return;
  }
  const auto& r = *view.hybrid();
  if (!r.covered) {
    ImGui::Text("frame %u: background (no G-buffer surface)", r.frameIndex);
    return;
  }
  ImGui::Text("frame %u at %s", r.frameIndex, vec3Text(r.position).c_str());
  ImGui::Text("normal %s", vec3Text(r.normal).c_str());
  ImGui::Text("sun: %s (average %.3f)",
              !r.shadowRay.traced   ? "below the surface"
              : r.shadowRay.visible ? "visible"
                                    : "blocked",
              r.shadowAverage);
  uint32_t open = 0;
  for (uint32_t i = 0; i < std::min(r.aoRays, WB_HYBRID_INSPECT_MAX_AO); ++i) open += r.aoRay[i].visible;
  ImGui::Text("AO: %u of %u rays open (average %.3f)", open, r.aoRays, r.aoAverage);
  if (!r.reflected) return;
  ImGui::Text("reflection %s", vec3Text(r.reflection).c_str());
  for (uint32_t b = 0; b < std::min(r.reflectionBounces, WB_HYBRID_INSPECT_MAX_REFLECTIONS); ++b) {
    const auto& x = r.bounces[b];
    if (!x.hit) {
      ImGui::Text("  %u: environment, added %s", b, vec3Text(x.added).c_str());
    } else {
      ImGui::Text("  %u: hit (rough %.2f metal %.2f, sun %s), added %s", b, x.roughness, x.metallic,
                  x.sunVisible > 0.0f ? "visible" : "blocked", vec3Text(x.added).c_str());
    }
  }
}

// The hybrid modes' rays of the pixel: the shadow ray dashed, AO rays short and thin (green open, red
// blocked), the reflection's bounces solid.
void drawHybridRays(ImDrawList* dl, const Projector& pr, const gpu::HybridInspectRecord& r, float radius) {
  if (r.frameIndex == WB_HYBRID_NO_INSPECT || !r.covered) return;
  ImVec2 a, b;
  auto visibility = [](uint32_t visible) {
    return visible ? IM_COL32(80, 230, 90, 255) : IM_COL32(230, 60, 60, 255);
  };
  if (r.shadowRay.traced && pr.segment(r.position, r.position + r.shadowRay.direction * radius * 0.35f, a, b))
    dashed(dl, a, b, visibility(r.shadowRay.visible));
  for (uint32_t i = 0; i < std::min(r.aoRays, WB_HYBRID_INSPECT_MAX_AO); ++i) {
    if (pr.segment(r.position, r.position + r.aoRay[i].direction * radius * 0.1f, a, b))
      dl->AddLine(a, b, (visibility(r.aoRay[i].visible) & 0x00ffffffu) | 0xa0000000u, 1.0f);
  }
  glm::vec3 from = r.position;
  const uint32_t bounces =
      r.reflected ? std::min(r.reflectionBounces, WB_HYBRID_INSPECT_MAX_REFLECTIONS) : 0u;
  for (uint32_t k = 0; k < bounces; ++k) {
    const auto& x = r.bounces[k];
    const glm::vec3 to = x.hit ? x.position : from + x.direction * radius * 0.5f;
    if (pr.segment(from, to, a, b)) dl->AddLine(a, b, throughputColor(luminance(x.throughput)), 2.0f);
    from = to;
  }
}

}  // namespace

std::optional<glm::vec2> projectToImage(const render::CameraState& camera, uint32_t width, uint32_t height,
                                        const glm::vec3& p) {
  glm::mat4 proj = glm::perspective(camera.yfov, float(width) / float(height), camera.znear, 1000.0f);
  proj[1][1] *= -1.0f;
  const glm::vec4 v = camera.view * glm::vec4(p, 1.0f);
  if (v.z > -camera.znear) return std::nullopt;
  const glm::vec4 clip = proj * v;
  return (glm::vec2(clip) / clip.w + 1.0f) * 0.5f * glm::vec2(width, height);
}

void drawInspectorSection(live::SessionState& st, const live::PixelInspection& view, bool pathTracing) {
  ImGui::Separator();
  ImGui::TextUnformatted(pathTracing ? "path inspector" : "ray inspector");
  ImGui::Checkbox("click picks the pixel", &st.inspectOnClick);
  if (!st.inspectPixel) {
    ImGui::TextDisabled("click the image (or set inspect_pixel X,Y) to record a pixel's %s",
                        pathTracing ? "paths" : "rays");
    return;
  }
  ImGui::Text("pixel %u,%u", st.inspectPixel->x, st.inspectPixel->y);
  ImGui::SameLine();
  if (ImGui::SmallButton("stop")) st.inspectPixel.reset();
  if (!pathTracing) {
    hybridSection(view);
    return;
  }
  const auto& e = view.estimate();
  const glm::dvec3 m = e.mean(), var = e.variance();
  ImGui::Text("samples %u (dropped %u), %zu kept", e.count(), e.dropped(), view.samples().size());
  ImGui::Text("mean     %.5g %.5g %.5g", m.x, m.y, m.z);
  ImGui::Text("variance %.4g %.4g %.4g", var.x, var.y, var.z);
  if (e.count() > 0) {
    const glm::dvec3 se = glm::sqrt(var / double(e.count()));
    ImGui::Text("std error %.3g %.3g %.3g", se.x, se.y, se.z);
  }
  const render::InspectedSample* s = view.shown(st.inspectShown);
  if (view.samples().empty() && !s) {
    ImGui::TextDisabled("waiting for a finished sample");
    return;
  }
  // The slider picks among the kept samples and the held one; the choice stays until another is picked.
  int first = view.samples().empty() ? st.inspectShown : int(view.samples().front().record.sampleIndex);
  int last = view.samples().empty() ? st.inspectShown : int(view.samples().back().record.sampleIndex);
  if (st.inspectShown >= 0) first = std::min(first, st.inspectShown), last = std::max(last, st.inspectShown);
  int chosen = st.inspectShown < 0 ? last : st.inspectShown;
  if (ImGui::SliderInt("sample", &chosen, first, last)) st.inspectShown = chosen;
  widgetRects().noteLastItem("inspect_sample");
  ImGui::SameLine();
  ImGui::Checkbox("all", &st.inspectAllSamples);
  widgetRects().noteLastItem("inspect_all");
  if (!s) return;
  const auto& r = s->record;
  ImGui::PushTextWrapPos(0.0f);
  ImGui::Text("sample %u%s: %s after %u vertices%s, value %.4g %.4g %.4g", r.sampleIndex,
              view.heldFromEarlier() ? " (held, from before the image restarted)" : " (held)",
              render::inspectEndName(r.end), r.vertexCount, s->truncated ? " (truncated)" : "", r.radiance.x,
              r.radiance.y, r.radiance.z);
  ImGui::PopTextWrapPos();
  if (s->firstNonFinite) {
    ImGui::TextColored(ImVec4(1, 0.3f, 1, 1), "first NaN/Inf: %s at %s",
                       render::inspectNonFiniteName(s->firstNonFinite->term),
                       s->firstNonFinite->vertex < 0
                           ? "the path's end"
                           : ("vertex " + std::to_string(s->firstNonFinite->vertex)).c_str());
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled(
      "# = bounce (0: the camera ray's hit); hover a row for the whole record; lines: "
      "throughput blue 0, green 1, red 2");
  ImGui::PopTextWrapPos();
  // Columns keep their width: a narrow panel scrolls the table sideways instead of cutting columns off.
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_Borders |
                                ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_ScrollX;
  const float height = (std::min(12.0f, float(s->vertices.size()) + 1.5f) + 1.0f) *
                       ImGui::GetTextLineHeightWithSpacing();  // + 1: the horizontal scroll bar
  if (ImGui::BeginTable("inspect_vertices", 9, flags, ImVec2(0.0f, height))) {
    for (const char* h : {"#", "mat", "dist", "lobe p", "pdf", "thru", "RR", "NEE", "clocks"})
      ImGui::TableSetupColumn(h);
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableHeadersRow();
    for (size_t k = 0; k < s->vertices.size(); ++k) {
      const auto& iv = s->vertices[k];
      const auto& v = iv.record;
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Selectable(std::to_string(k).c_str(), false, ImGuiSelectableFlags_SpanAllColumns);
      const bool hovered = ImGui::IsItemHovered();
      ImGui::TableNextColumn();
      ImGui::Text("%d", v.material);
      ImGui::TableNextColumn();
      ImGui::Text("%.3g", v.distance);
      ImGui::TableNextColumn();
      ImGui::Text("%c %.2f",
                  v.lobe == WB_LOBE_SPECULAR    ? 'S'
                  : v.lobe == WB_LOBE_REFLECTOR ? 'R'
                                                : 'D',
                  v.lobeProbability);
      ImGui::TableNextColumn();
      ImGui::Text("%.3g", v.pdf);
      ImGui::TableNextColumn();
      ImGui::Text("%.3g", luminance(v.throughput));
      ImGui::TableNextColumn();
      ImGui::Text("%s", v.rrOutcome == WB_INSPECT_RR_NOT_APPLIED ? "-"
                        : v.rrOutcome == WB_INSPECT_RR_SURVIVED  ? "ok"
                                                                 : "end");
      ImGui::TableNextColumn();
      std::string nee;
      for (const auto& l : iv.lights) {
        nee += l.status != WB_INSPECT_NEE_TRACED ? '.' : l.visible ? '+' : 'x';
      }
      ImGui::Text("%s", nee.empty() ? "-" : nee.c_str());
      ImGui::TableNextColumn();  // the vertex's trace call, shading and shadow rays (0: no shader clock)
      const double clocks = double(v.traceClocks) + v.shadeClocks + v.shadowClocks;
      if (clocks > 0) {
        ImGui::Text("%.3g", clocks);
      } else {
        ImGui::TextUnformatted("-");
      }
      if (hovered) vertexTooltip(iv);
    }
    ImGui::EndTable();
  }
  if (r.escaped) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::Text("escaped: environment %s, MIS %.3g, sun %s", vec3Text(r.escapeEnvironment).c_str(),
                r.escapeMis, vec3Text(r.escapeSun).c_str());
    ImGui::PopTextWrapPos();
  }
}

void drawInspectorOverlay(const live::SessionState& st, const live::PixelInspection& view,
                          const render::CameraState& camera, uint32_t traceWidth, uint32_t traceHeight,
                          const Rect& image, float sceneRadius) {
  if (!st.inspectPixel || traceWidth == 0 || traceHeight == 0) return;
  glm::mat4 proj =
      glm::perspective(camera.yfov, float(traceWidth) / float(traceHeight), camera.znear, 1000.0f);
  proj[1][1] *= -1.0f;
  const Projector pr{camera.view, proj, camera.znear, glm::vec2(traceWidth, traceHeight), image};
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->PushClipRect(ImVec2(image.x, image.y), ImVec2(image.x + image.w, image.y + image.h), true);
  if (view.hybrid()) drawHybridRays(dl, pr, *view.hybrid(), sceneRadius);
  // The records are the pixel's once the frame after the pick has read them; the marker shows at once.
  if (view.pixel() == st.inspectPixel) {
    const render::InspectedSample* shown = view.shown(st.inspectShown);
    if (st.inspectAllSamples) {
      for (const auto& s : view.samples())
        if (&s != shown) drawPath(dl, pr, s, sceneRadius, true);
    }
    if (shown) drawPath(dl, pr, *shown, sceneRadius, false);
  }
  // The pixel itself.
  const float sx = image.w / float(traceWidth), sy = image.h / float(traceHeight);
  const ImVec2 a(image.x + float(st.inspectPixel->x) * sx, image.y + float(st.inspectPixel->y) * sy);
  dl->AddRect(ImVec2(a.x - 2, a.y - 2), ImVec2(a.x + std::max(sx, 1.0f) + 2, a.y + std::max(sy, 1.0f) + 2),
              IM_COL32(255, 255, 0, 255), 0.0f, 0, 1.5f);
  dl->PopClipRect();
}

}  // namespace wb::app
