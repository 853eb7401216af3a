#include "app/window/widget_rects.h"

#include <imgui.h>

namespace wb::app {

void WidgetRects::noteLastItem(const std::string& name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  note(name, Rect{a.x, a.y, b.x - a.x, b.y - a.y});
}

WidgetRects& widgetRects() {
  static WidgetRects rects;
  return rects;
}

}  // namespace wb::app
