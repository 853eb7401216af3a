// The JSON form of a reload event (one line of `watch --log`, and the UI's history export).
#pragma once
#include <nlohmann/json.hpp>

#include "render/hot_reload.h"

namespace wb::app {

nlohmann::json reloadEventJson(const render::ReloadEvent& e);

}  // namespace wb::app
