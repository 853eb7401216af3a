// The JSON form of a reload event (one line of `watch --log`, and the UI's history export).
#pragma once
#include <nlohmann/json.hpp>

#include "live/hot_reload.h"

namespace wb::app {

nlohmann::json reloadEventJson(const live::ReloadEvent& e);
// The "ab" object of a reload line: exactly image_verdict, rmse, rel_mse, max_abs_diff,
// changed_pixel_fraction, mean_shift_significant, speed_ratio, speed_ratio_spread ([min, max] of the rounds'
// ratios), speed_verdict.
nlohmann::json abJson(const live::ReloadAB& ab);

}  // namespace wb::app
