// What the window reports and saves of its session: the parameters of what is shown (the saved render's JSON
// sidecar and the stats' "parameters"), the session's statistics (`stats`, `--stats`; the window adds its own
// keys), a saved render (F12, `save`) and the inspected pixel's records (`inspect`).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "app/window/camera_controller.h"
#include "live/live_session.h"

namespace wb::app {

nlohmann::json parametersJson(live::LiveSession& session, const CameraController& camera);
nlohmann::json sessionStatsJson(live::LiveSession& session);
// BASE.png (tonemapped), BASE.exr (linear), BASE.json (parameters); "" names one under out/. Returns what the
// panel says of it.
std::string saveRender(live::LiveSession& session, const CameraController& camera, std::string base);
// The inspected pixel's records now (the device must be idle), as `render --inspect-out` writes them plus the
// running estimate; the hybrid modes' record of the pixel's rays. Throws when no pixel is inspected.
void writeInspection(live::LiveSession& session, const std::string& path);

}  // namespace wb::app
