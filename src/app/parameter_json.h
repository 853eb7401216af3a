// Every parameter as JSON, one schema for every writer (render --stats, the window's stats and saved
// parameters, converge and bench reports): {"name": value}, numbers as numbers, colours as [r, g, b], choices
// and paths as strings.
#pragma once
#include <nlohmann/json.hpp>

#include "render/parameters.h"

namespace wb::app {

nlohmann::json parametersJson(const render::Parameters& values);

}  // namespace wb::app
