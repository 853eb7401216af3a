#include "app/window/parameter_panel.h"

#include <algorithm>
#include <map>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "app/window/widget_rects.h"

namespace wb::app {

bool drawParameter(const render::ParameterInfo& p, render::Parameters& values) {
  using render::ParameterType;
  const render::ParameterValue v = p.get(values);
  ImGui::PushID(p.name.c_str());
  bool changed = false;
  render::ParameterValue next = v;
  switch (p.type) {
    case ParameterType::Bool: {
      bool b = std::get<bool>(v);
      if ((changed = ImGui::Checkbox(p.label.c_str(), &b))) next = b;
      break;
    }
    case ParameterType::UInt: {
      int i = int(std::min<uint32_t>(std::get<uint32_t>(v), uint32_t(INT32_MAX)));
      changed = p.uiMin < p.uiMax ? ImGui::SliderInt(p.label.c_str(), &i, int(p.uiMin), int(p.uiMax))
                                  : ImGui::InputInt(p.label.c_str(), &i);
      if (changed) next = uint32_t(std::clamp<double>(i, p.min, p.max));
      break;
    }
    case ParameterType::Float: {
      float f = std::get<float>(v);
      changed = p.uiMin < p.uiMax
                    ? ImGui::SliderFloat(p.label.c_str(), &f, float(p.uiMin), float(p.uiMax), "%.3g")
                    : ImGui::DragFloat(p.label.c_str(), &f, 0.01f, float(p.min), float(p.max), "%.3g");
      if (changed) next = float(std::clamp<double>(f, p.min, p.max));
      break;
    }
    case ParameterType::Color: {
      glm::vec3 c = std::get<glm::vec3>(v);
      if ((changed =
               ImGui::ColorEdit3(p.label.c_str(), &c.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)))
        next = glm::max(c, glm::vec3(0.0f));
      break;
    }
    case ParameterType::Choice: {
      const std::string& current = std::get<std::string>(v);
      // Every choice shown at once (the debug views are ten): no scrolling inside the list.
      if (ImGui::BeginCombo(p.label.c_str(), current.c_str(), ImGuiComboFlags_HeightLarge)) {
        for (const auto& c : p.choices) {
          if (ImGui::Selectable(c.c_str(), c == current) && c != current) {
            next = c;
            changed = true;
          }
          widgetRects().noteLastItem("param." + p.name + "." + c);
        }
        ImGui::EndCombo();
      }
      break;
    }
    case ParameterType::Path: {
      // Edited in a field of its own and applied with Load (or Enter), not on every keystroke.
      static std::map<std::string, std::string> edits;
      auto [it, inserted] = edits.try_emplace(p.name, std::get<std::string>(v));
      const bool enter = ImGui::InputText("##path", &it->second, ImGuiInputTextFlags_EnterReturnsTrue);
      ImGui::SameLine();
      if ((ImGui::Button("Load") || enter) && it->second != std::get<std::string>(v)) {
        next = it->second;
        changed = true;
      }
      ImGui::SameLine();
      ImGui::TextUnformatted(p.label.c_str());
      break;
    }
  }
  widgetRects().noteLastItem("param." + p.name);
  if (ImGui::IsItemHovered() && !p.help.empty()) ImGui::SetTooltip("%s", p.help.c_str());
  if (changed) p.put(values, next);
  ImGui::PopID();
  return changed;
}

bool drawParameterGroup(const std::string& group, render::Parameters& values, render::RenderMode mode) {
  bool changed = false;
  for (const auto& p : render::parameterList()) {
    if (p.group == group && p.usedIn(mode)) changed |= drawParameter(p, values);
  }
  return changed;
}

}  // namespace wb::app
