// What a command that renders takes from its command line (a contract with scripts outside the project:
// names are stable): the scene, the launch options (size, tiles, defines, AOVs, device) and every parameter's
// flag (render/parameters.h).
#pragma once
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/parameter_cli.h"
#include "render/parameters.h"

namespace wb::app {

struct RenderOptions {
  std::string scene;  // empty = the default scene
  std::string size = "512x512";
  // Every parameter; its render settings also carry the launch options below once finished.
  render::Parameters params;
  std::string aov;                            // "albedo,normal,cost"
  bool aovAlbedo = false, aovNormal = false;  // which --aov images to write
  bool aovCost = false;                       // the path tracer's cost variant and its cost map
  std::vector<std::string> defines;           // --define K=V
  std::string device;
  std::string tile;              // "WxH": dispatch shape of a sample (default: the whole image)
  std::string samplesPerLaunch;  // "N": samples per ray tracing launch (default: the device's choice)
  ParameterFlags flags;

  const render::RenderSettings& settings() const { return params.render; }
};

// Adds SCENE, the launch options and every parameter's flag to a CLI11 command.
void addRenderOptions(CLI::App& app, RenderOptions& o);
// Validates and converts the parsed strings into o.params; throws std::invalid_argument with a one-line
// reason naming the flag.
void finishRenderOptions(RenderOptions& o);

}  // namespace wb::app
