// Everything the user (the panels) or a script can change in the live workbench. The frame loop compares it
// with what the renderer has and applies the difference: image-altering changes restart accumulation,
// display-only ones (exposure, tonemapper, debug view) do not.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "display/display_types.h"
#include "eval/image.h"
#include "render/hybrid/hybrid_settings.h"
#include "render/settings.h"
#include "shared/gpu_types.h"

namespace wb::app {

struct DisplaySettings {
  float exposure = 0.0f;  // stops
  eval::Tonemap tonemap = eval::Tonemap::Aces;
  uint32_t view = WB_VIEW_BEAUTY;
};

struct WorkbenchState {
  render::RenderSettings settings;  // width/height are ignored: the view size x resolutionScale decides
  DisplaySettings display;
  // Path tracer or one of its fast, biased counterparts; changing it restarts accumulation.
  render::RenderMode mode = render::RenderMode::PathTrace;
  render::HybridSettings hybrid;
  float resolutionScale = 0.5f;
  bool fixedSize = false;  // --size given: trace at that size whatever the window
  uint32_t fixedWidth = 0, fixedHeight = 0;
  uint32_t targetSpp = 0;  // 0 = keep refining
  bool paused = false;
  bool preview = true;
  float budgetMs = 30.0f;
  bool vsync = true;
  bool showPanel = true;

  std::vector<gpu::Material> materials;  // live copies, edited in Inspect
  bool materialsDirty = false;
  std::vector<gpu::DirectionalLight> lights;  // live copies, edited in Lights
  bool lightsDirty = false;

  // One-shot requests (the frame loop clears them).
  bool resetAccumulation = false;
  bool resetCamera = false;
  bool reloadShaders = false;
  std::optional<std::string> saveRequest;  // base path without extension ("" = automatic name)
  bool quit = false;

  std::string envError;  // why the last environment change failed

  // The running error panel: a reference .exr to compare with (empty = the noise estimate).
  std::string referencePath;
};

const char* viewName(uint32_t view);
std::optional<uint32_t> viewFromName(const std::string& name);
std::optional<eval::Tonemap> tonemapFromName(const std::string& name);

// Applies NAME=VALUE (or NAME VALUE) to the state: the names `--set` and scripts use. Throws
// std::invalid_argument with a one-line reason.
void applySetting(WorkbenchState& state, const std::string& name, const std::string& value);
// The names applySetting knows, for --help.
const char* settingNamesHelp();

}  // namespace wb::app
