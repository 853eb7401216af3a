// Scenes built around one numerical risk each (grazing incidence, roughness extremes, a tiny sun, extreme
// scales, degenerate triangles, broken tangents, long specular chains, alpha-masked foliage), for
// `workbench converge --hard-cases`. Most are white furnaces: energy-preserving white materials in a uniform
// environment of radiance 1, where every pixel converges to furnaceValue.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace wb::scene {

struct HardCase {
  std::string name;
  std::string risk;
  Scene scene;
  std::vector<std::string> variants;  // render flags per row ("" = defaults)
  // Scene-specific parameters (environment, bounces) as NAME=VALUE, named as the parameter registry
  // (render/parameters.h) and `--set` name them; they apply over each variant's flags.
  std::vector<std::string> settings;
  uint32_t minBounces = 0;  // max_bounces is raised to at least this (a furnace needs long paths to reach 1)
  double furnaceValue = 0;  // > 0: expected pixel value (energy check)
  std::string note;
};

std::vector<HardCase> hardCases();

}  // namespace wb::scene
