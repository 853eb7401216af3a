// The colour bar of the window's heat-map views (bounces, rr_end, variance, nan_source): the display shader's
// ramp (shaders/shared/heat_ramp.h heatRamp) with what its colours mean, their units and scale, drawn at
// the image's bottom right.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "app/window/rect.h"

namespace wb::app {

struct HeatLegend {
  std::string title;                                 // the view and the quantity, with its unit
  std::vector<std::pair<float, std::string>> ticks;  // position 0..1 along the ramp, label
  std::string note;                                  // what a colour outside the ramp means ("" none)
};

// The display shader's heat ramp at t (clamped to 0..1), linear RGB.
glm::vec3 heatRampColour(float t);
// The legend of debug view `view` (WB_VIEW_*), or nullopt when the view is no heat map. `maxVertices`: the
// path tracer's vertices per path (the display's scale of the bounce views).
std::optional<HeatLegend> heatLegend(uint32_t view, float maxVertices);
// Draws `legend` in the bottom right corner of `image`; returns the rectangle it covers.
Rect drawHeatLegend(const HeatLegend& legend, const Rect& image);

}  // namespace wb::app
