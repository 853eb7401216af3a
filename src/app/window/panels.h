// The workbench's ImGui panels (Render, Inspect, Lights and environment, Shaders, Stats) and the overlays on
// the image (status line, shader error banner). They only edit live::SessionState; the frame loop applies it.
#pragma once
#include <optional>
#include <string>

#include "app/window/camera_controller.h"
#include "app/window/frame_stats.h"
#include "app/window/path_inspector_view.h"
#include "app/window/pixel_picker.h"
#include "app/window/rect.h"
#include "live/live_session.h"
#include "scene/scene.h"
#include "shader/library.h"

namespace wb::app {

// What the panels show: the session (which knows the mode, its samples and its state) and the window's own
// parts.
struct PanelContext {
  live::LiveSession& session;
  CameraController& camera;
  const std::optional<PickResult>& hover;     // under the cursor
  const std::optional<PickResult>& selected;  // clicked: the material editor edits it
  const FrameStats& frames;
  std::string presentMode;
  std::string lastSaved;
  double displayGpuMs = 0;  // the display pass's GPU time in the last frame
};

// The side panel's default width in a window of that width.
float sidePanelWidth(float windowWidth);
// The side panel at `width` (0: the default; the user drags its right edge to resize it, which updates
// `width`); returns its width in pixels (0 when hidden).
float drawSidePanel(PanelContext& c, float windowWidth, float windowHeight, float& width);
// Status line and the shader error banner over the image area.
void drawOverlays(PanelContext& c, const Rect& view);


}  // namespace wb::app
