// The colour bar of the window's heat-map views (bounces, rr_end, variance, nan_source, cost, inefficiency):
// the display shader's ramp (shaders/shared/heat_ramp.h heatRamp) with what its colours mean, their units and
// scale, drawn at the image's bottom right. The one legend style of every heat map; panels add numbers only.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "app/window/rect.h"
#include "eval/cost_map.h"

namespace wb::app {

struct HeatLegend {
  std::string title;                                 // the view and the quantity, with its unit
  std::vector<std::pair<float, std::string>> ticks;  // position 0..1 along the ramp, label
  std::string note;                                  // what a colour outside the ramp means ("" none)
};

// The display shader's heat ramp at t (clamped to 0..1), linear RGB.
glm::vec3 heatRampColour(float t);
// The legend of debug view `view` (WB_VIEW_*), or nullopt when the view is no heat map or, for the cost
// views, when there is no cost data (`cost` null or not valid: the panel says why). `maxVertices`: the path
// tracer's vertices per path (the display's scale of the bounce views); `cost`: the cost views' scale.
std::optional<HeatLegend> heatLegend(uint32_t view, float maxVertices,
                                     const eval::CostSummary* cost = nullptr);
// Draws `legend` in the bottom right corner of `image`; returns the rectangle it covers.
Rect drawHeatLegend(const HeatLegend& legend, const Rect& image);

}  // namespace wb::app
