// Scenes built around one numerical risk each (grazing incidence, roughness extremes, a tiny sun, extreme
// scales, degenerate triangles, broken tangents, long specular chains, alpha-masked foliage), for
// `workbench converge --hard-cases`. Most are white furnaces: energy-preserving white materials in a uniform
// environment of radiance 1, where every pixel converges to furnaceValue.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "render/settings.h"
#include "scene/scene.h"

namespace wb::eval {

struct HardCase {
  std::string name;
  std::string risk;
  scene::Scene scene;
  std::vector<std::string> variants;                    // render flags per row ("" = defaults)
  std::function<void(render::RenderSettings&)> adjust;  // scene-specific settings (environment, bounces)
  double furnaceValue = 0;                              // > 0: expected pixel value (energy check)
  std::string note;
};

std::vector<HardCase> hardCases();

}  // namespace wb::eval
