// Where the window drew its named widgets in the last frame (framebuffer pixels): the stats JSON lists them
// ("widgets"), so that tests and the bench click real widgets wherever the layout puts them.
#pragma once
#include <map>
#include <string>

#include "app/window/rect.h"

namespace wb::app {

class WidgetRects {
 public:
  // A new frame: the widgets it draws replace the last frame's.
  void beginFrame() { rects_.clear(); }
  void note(const std::string& name, const Rect& r) { rects_[name] = r; }
  // The last ImGui item's rectangle (call right after the item).
  void noteLastItem(const std::string& name);
  const std::map<std::string, Rect>& rects() const { return rects_; }

 private:
  std::map<std::string, Rect> rects_;
};

// The window's one list (the panels are free functions).
WidgetRects& widgetRects();

}  // namespace wb::app
