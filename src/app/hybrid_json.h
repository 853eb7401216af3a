// The hybrid renderer's effective parameters as the `--stats` JSON (render) and the window's stats and
// saved-image sidecar write them: one definition of the keys.
#pragma once
#include <nlohmann/json.hpp>

#include "render/hybrid/hybrid_renderer.h"

namespace wb::app {

nlohmann::json hybridSettingsJson(const render::HybridRenderer& hybrid);

}  // namespace wb::app
