// A rectangle of the window in framebuffer pixels (the view beside the panel, the image in it).
#pragma once

namespace wb::app {

struct Rect {
  float x = 0, y = 0, w = 0, h = 0;
  bool contains(float px, float py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

}  // namespace wb::app
