// Everything the user (the panels) or a script can change in the live workbench. The frame loop compares it
// with what the renderer has and applies the difference: parameters that restart accumulation do
// (ParameterInfo::resetsAccumulation), the display ones (exposure, tonemapper, debug view) do not.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "display/display_types.h"
#include "render/parameters.h"
#include "shared/gpu_types.h"

namespace wb::live {

struct SessionState {
  // Every parameter (render/parameters.h). params.render's size is the view size x resolutionScale (or
  // --size); params.render.spp is the target (0 = keep refining).
  render::Parameters params;
  float resolutionScale = 0.5f;
  bool fixedSize = false;  // --size given: trace at that size whatever the window
  uint32_t fixedWidth = 0, fixedHeight = 0;
  bool paused = false;
  bool preview = true;
  float budgetMs = 30.0f;
  bool vsync = true;
  bool showPanel = true;

  std::vector<gpu::Material> materials;  // live copies, edited in Inspect
  bool materialsDirty = false;
  std::vector<gpu::DirectionalLight> lights;  // live copies, edited in Lights
  bool lightsDirty = false;

  // The path inspector (Inspect tab): the pixel of the trace image whose paths are recorded (nullopt: off;
  // setting one switches the path tracer to its inspecting variant and restarts accumulation), how many of
  // the latest samples are kept, which one the table and the overlay show (-1: none chosen yet: the first to
  // arrive is; it is held until another is chosen or the pixel changes), whether a click on the image picks
  // the pixel.
  std::optional<glm::uvec2> inspectPixel;
  uint32_t inspectSamples = 64;
  int inspectShown = -1;
  bool inspectOnClick = true;
  bool inspectAllSamples = false;  // the overlay draws every kept sample's path, not only the shown one
  // A pixel was picked: the panel opens the Inspect section and scrolls to it for this many frames (the
  // panel's scroll range includes the section's contents from the frame after it opened).
  int inspectOpenPanel = 0;
  // wbAssert checked at every pixel (the path tracer's asserts variant; restarts accumulation).
  bool asserts = false;

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

// Applies NAME=VALUE (or NAME VALUE) to the state: every parameter under its name or its flag's
// (render/parameters.h), and the window's own settings. Throws std::invalid_argument with a one-line reason;
// the state is unchanged then.
void applySetting(SessionState& state, const std::string& name, const std::string& value);
// The names applySetting knows, for --help.
std::string settingNamesHelp();

}  // namespace wb::live
