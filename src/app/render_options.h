// Command-line flags shared by `render`, the window and the other commands that render (a contract with
// scripts outside the project: names are stable).
#pragma once
#include <string>

#include <CLI/CLI.hpp>

#include "render/hybrid/hybrid_settings.h"
#include "render/settings.h"

namespace wb::app {

struct RenderOptions {
  std::string scene;  // empty = the default scene
  std::string size = "512x512";
  render::RenderSettings settings;
  std::string envColor;  // "R,G,B"
  std::string sampler = "owen";
  std::string aov;                            // "albedo,normal"
  bool aovAlbedo = false, aovNormal = false;  // which --aov images to write
  std::vector<std::string> defines;           // --define K=V
  std::string device;
  std::string tile;  // "WxH": dispatch shape of a sample (default: the whole image)
  bool noRussianRoulette = false;
  bool noNee = false;
  bool noMis = false;
  // --mode pathtrace|hybrid|reflections and the hybrid modes' parameters.
  std::string modeName = "pathtrace";
  render::RenderMode mode = render::RenderMode::PathTrace;
  render::HybridSettings hybrid;
  bool noTemporal = false;
};

// Adds SCENE and the render parameter flags to a CLI11 command.
void addRenderOptions(CLI::App& app, RenderOptions& o);
// Validates and converts the parsed strings into o.settings; throws std::invalid_argument with a one-line
// reason.
void finishRenderOptions(RenderOptions& o);

}  // namespace wb::app
