// The workbench's ImGui panels (Render, Inspect, Lights and environment, Shaders, Stats) and the overlays on
// the image (status line, shader error banner). They only edit WorkbenchState; the frame loop applies it.
#pragma once
#include <optional>
#include <string>

#include "app/window/camera_controller.h"
#include "app/window/frame_stats.h"
#include "app/window/path_inspector_view.h"
#include "app/window/pixel_picker.h"
#include "app/window/progressive.h"
#include "app/window/workbench_state.h"
#include "eval/live_error.h"
#include "live/hot_reload.h"
#include "render/hybrid/hybrid_renderer.h"
#include "scene/scene.h"
#include "shader/library.h"

namespace wb::app {

struct Rect {
  float x = 0, y = 0, w = 0, h = 0;
  bool contains(float px, float py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

struct PanelContext {
  WorkbenchState& state;
  const scene::Scene& scene;
  const ProgressiveTracer& progressive;
  live::HotReload& hot;
  shader::ShaderLibrary& library;
  CameraController& camera;
  const std::optional<PickResult>& pick;
  const FrameStats& frames;
  const gpu::Counters& counters;
  double traceSeconds;  // GPU time spent tracing since the last restart
  std::string deviceName;
  std::string presentMode;
  uint32_t traceWidth = 0, traceHeight = 0;
  std::string lastSaved;
  const render::HybridRenderer* hybrid = nullptr;  // the active hybrid renderer (hybrid modes only)
  uint32_t samples = 0;                            // finished samples (path tracer) or frames (hybrid)
  double secondsSinceReset = 0;
  const eval::LiveError* liveError = nullptr;
  std::string modeSwitch;  // the mode being prepared off the frame loop (empty: none)
  double modeSwitchSeconds = 0;
  const InspectorView* inspector = nullptr;  // the path inspector's records (Inspect tab, image overlay)
};

// The side panel's width in a window of that width (when shown).
float sidePanelWidth(float windowWidth);
// The side panel; returns its width in pixels (0 when hidden).
float drawSidePanel(PanelContext& c, float windowWidth, float windowHeight);
// Status line and the shader error banner over the image area.
void drawOverlays(PanelContext& c, const Rect& view);

// "12.3 M" style numbers.
std::string humanCount(double v);

}  // namespace wb::app
